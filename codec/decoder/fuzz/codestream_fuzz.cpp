// libFuzzer target for the decoder: any bytes, as a codestream or a JP2 file, must decode or give
// a one-line DecodeError; never a crash, a hang, a sanitizer report or another exception. The
// memory limit is kept small so that the fuzzer explores headers rather than allocating.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "codec/decoder/decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  codec::DecodeOptions options;
  options.threads = 1;
  options.max_memory = std::size_t{64} << 20;
  // The input's length picks a window and a component selection for some inputs, so that the
  // paths that skip tiles, code-blocks and components are fuzzed too.
  if (size % 3 == 1) options.region = codec::DecodeRegion{static_cast<std::int64_t>(size % 7), 2, 37, 29};
  if (size % 5 == 2) options.components = {0};
  try {
    const codec::DecodedImage image = codec::decode(std::span<const std::uint8_t>(data, size), options);
    // Each component's samples, in `samples` or (more than 31 bits) `wide_samples`, the other empty.
    for (const auto& c : image.components) {
      const std::size_t count = static_cast<std::size_t>(c.width) * static_cast<std::size_t>(c.height);
      const bool wide = c.precision > 31;
      if (c.samples.size() != (wide ? 0 : count) || c.wide_samples.size() != (wide ? count : 0)) std::abort();
    }
  } catch (const codec::DecodeError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();  // the one-line promise
  }
  return 0;
}
