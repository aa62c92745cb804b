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

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const imageio::Image image = imageio::parse_pnm(std::span(data, size), "fuzz-input");
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
  } catch (const imageio::IoError&) {
    // Expected for malformed input.
  }
  return 0;
}
