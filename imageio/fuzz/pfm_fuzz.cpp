// libFuzzer entry point for the PFM parser. Rejected input must surface as
// IoError; any other exception, crash or sanitizer report is a bug.
//
//   cmake -DCMAKE_CXX_COMPILER=clang++ -DGPUJ2K_FUZZ=ON ... && build/bin/pfm_fuzz

#include <cstddef>
#include <cstdint>
#include <span>

#include "imageio/pfm.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const imageio::Image image = imageio::parse_pfm(std::span(data, size), "fuzz-input");
    // Touch every sample so that wrong sizes show up under ASan.
    volatile float sink = 0;
    for (float v : image.pixels) sink = sink + v;
  } catch (const imageio::IoError&) {
    // Expected for malformed input.
  }
  return 0;
}
