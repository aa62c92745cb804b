// libFuzzer entry point for the PNM (PBM/PGM/PPM) parser. Rejected input must
// surface as IoError; any other exception, crash or sanitizer report is a bug,
// and so is an accepted image that breaks the parser's promises.
//
//   cmake -DCMAKE_CXX_COMPILER=clang++ -DGPUJ2K_FUZZ=ON ... && build/bin/pnm_fuzz

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "imageio/pnm.h"

// The planar reader must agree with the interleaved one on every input: the same error or the
// same samples.
void check_planar(std::span<const std::uint8_t> bytes, const imageio::Image* image) {
  try {
    const imageio::PlanarImage planar = imageio::parse_pnm_planar(bytes, "fuzz-input");
    if (image == nullptr || planar.width != image->width || planar.height != image->height ||
        planar.channels != image->channels || planar.bits_per_sample != image->bits_per_sample ||
        planar.planes.size() != std::size_t(image->channels))
      std::abort();
    const std::size_t pixels = std::size_t(image->width) * std::size_t(image->height);
    for (std::size_t c = 0; c < planar.planes.size(); ++c) {
      if (planar.planes[c].size() != pixels) std::abort();
      for (std::size_t p = 0; p < pixels; ++p)
        if (float(planar.planes[c][p]) != image->pixels[p * planar.planes.size() + c]) std::abort();
    }
  } catch (const imageio::IoError&) {
    if (image != nullptr) std::abort();
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  try {
    const imageio::Image image = imageio::parse_pnm(bytes, "fuzz-input");
    if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
        image.bits_per_sample < 1 || image.bits_per_sample > 16 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels)) {
      std::abort();
    }
    // Touch every sample so that wrong sizes show up under ASan, and check
    // that each fits in bits_per_sample.
    const float top = float((1 << image.bits_per_sample) - 1);
    for (float v : image.pixels) {
      if (!(v >= 0 && v <= top)) std::abort();
    }
    check_planar(bytes, &image);
  } catch (const imageio::IoError&) {
    // Expected for malformed input.
    check_planar(bytes, nullptr);
  }
  return 0;
}
