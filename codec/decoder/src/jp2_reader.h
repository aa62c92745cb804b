#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

namespace codec::dec {

// What the decoder takes from a JP2 file (T.800 Annex I): where the codestream lies and the
// header facts that change the output.
struct Jp2File {
  std::span<const std::uint8_t> codestream;
  std::size_t codestream_offset = 0;
  int colour_space = 0;  // colr method 1's EnumCS, 0 if none
};

bool looks_like_jp2(std::span<const std::uint8_t> bytes);
// Walks the boxes, every length checked. Throws DecodeError for a malformed file and for features
// the decoder does not apply yet (palettes).
Jp2File read_jp2(std::span<const std::uint8_t> bytes);

}  // namespace codec::dec
