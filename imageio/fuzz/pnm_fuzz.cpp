// libFuzzer entry point for the PNM (PBM/PGM/PPM) parser. Rejected input must
// surface as IoError; any other exception, crash or sanitizer report is a bug,
// and so is an accepted image that breaks the parser's promises.
//
//   cmake -DCMAKE_CXX_COMPILER=clang++ -DGPUJ2K_FUZZ=ON ... && build/bin/pnm_fuzz

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "imageio/pnm.h"

// The packed reader must agree with the interleaved one on every input: the same error or the
// same samples.
void check_packed(std::span<const std::uint8_t> bytes, const imageio::Image* image) {
  try {
    const imageio::PackedImage packed = imageio::parse_pnm_packed(bytes, "fuzz-input");
    if (image == nullptr || packed.width != image->width || packed.height != image->height ||
        packed.channels != image->channels || packed.bits_per_sample != image->bits_per_sample ||
        packed.bytes_per_sample != (packed.bits_per_sample > 8 ? 2 : 1) || packed.raster == nullptr)
      std::abort();
    std::vector<std::int32_t> row(std::size_t(image->width));
    for (int y = 0; y < image->height; ++y)
      for (int c = 0; c < image->channels; ++c) {
        packed.unpack_row(c, y, 0, image->width, row.data());
        for (int x = 0; x < image->width; ++x)
          if (float(row[std::size_t(x)]) != image->at(x, y, c)) std::abort();
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
    check_packed(bytes, &image);
  } catch (const imageio::IoError&) {
    // Expected for malformed input.
    check_packed(bytes, nullptr);
  }
  return 0;
}
