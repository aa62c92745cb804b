#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace codec::ht {

// The HT cleanup pass (T.814 7.3, the encoder's view): `magnitudes` holds width * height values
// mu (the quantisation indices' magnitudes with the planes below the cleanup plane already
// dropped), row by row, and `negative` their signs (non-zero: negative). Returns the cleanup
// segment Dcup: MagSgn bytes, MEL bytes, VLC bytes, with Scup in the last two bytes. Every mu must
// be below 2^31 - 1; a block with no significant sample has no cleanup pass and must not be passed.
// Throws std::invalid_argument for sizes outside 1..1024 with width * height <= 4096.
std::vector<std::uint8_t> encode_cleanup(std::span<const std::uint32_t> magnitudes,
                                         std::span<const std::uint8_t> negative, int width, int height);

}  // namespace codec::ht
