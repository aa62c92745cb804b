#pragma once
#include <cstddef>
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
//
// Adjusting (ht_block_encoder.cpp; README, "Raising near-significant samples" and "Lowering quads'
// exponents"): with `adjustment`, whose fractions (the magnitudes', in 256ths) hold one per sample
// and plane <= 23, samples below 2^plane whose magnitude * 256 + fraction reaches raise_threshold
// (0: none; `negative` must then hold zero magnitudes' signs) are coded as index 1 in quads already
// significant, and quads whose largest exponent it pays to lower have their samples at it coded one
// index lower (simd::adjust_quad_row). Their row-major indices are appended to `raised` and
// `lowered`.
struct CleanupAdjustment {
  std::span<const std::uint8_t> fractions;
  std::uint32_t raise_threshold = 0;
  std::vector<std::size_t>* raised = nullptr;
  std::vector<std::size_t>* lowered = nullptr;
};

std::vector<std::uint8_t> encode_cleanup(std::span<const std::uint32_t> magnitudes,
                                         std::span<const std::uint8_t> negative, std::span<const std::uint8_t> lengths,
                                         std::span<const std::uint8_t> lengths_below_top, int width, int height,
                                         int plane = 0, const CleanupAdjustment* adjustment = nullptr);

}  // namespace codec::ht
