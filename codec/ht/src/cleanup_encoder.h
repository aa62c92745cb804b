#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace codec::ht {

// The HT cleanup pass (T.814 7.3, the encoder's view) on bit-plane `plane`: `magnitudes` holds
// width * height quantisation indices' magnitudes, row by row, and `negative` their signs
// (non-zero: negative); the pass codes mu = magnitude >> plane. Returns the cleanup segment Dcup:
// MagSgn bytes, MEL bytes, VLC bytes, with Scup in the last two bytes. Every mu must be below
// 2^31 - 1; a block with no significant mu has no cleanup pass and must not be passed.
// `lengths` and `lengths_below_top` as HtBlock's. Throws std::invalid_argument for sizes outside
// 1..1024 with width * height <= 4096, or spans of another size.
std::vector<std::uint8_t> encode_cleanup(std::span<const std::uint32_t> magnitudes,
                                         std::span<const std::uint8_t> negative, std::span<const std::uint8_t> lengths,
                                         std::span<const std::uint8_t> lengths_below_top, int width, int height,
                                         int plane = 0);

}  // namespace codec::ht
