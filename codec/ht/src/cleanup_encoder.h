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
// Lowering (ht_block_encoder.cpp; README, "Lowering quads' exponents"): with `lowering`, whose
// fractions (the magnitudes', in 256ths) must hold one per sample and plane <= 23, quads whose
// largest exponent it pays to lower (simd::lower_quad_row) have their samples at it coded one index
// lower; their row-major indices are appended to `lowered`.
struct CleanupLowering {
  std::span<const std::uint8_t> fractions;
  std::vector<std::size_t>* lowered = nullptr;
};

std::vector<std::uint8_t> encode_cleanup(std::span<const std::uint32_t> magnitudes,
                                         std::span<const std::uint8_t> negative, std::span<const std::uint8_t> lengths,
                                         std::span<const std::uint8_t> lengths_below_top, int width, int height,
                                         int plane = 0, const CleanupLowering* lowering = nullptr);

}  // namespace codec::ht
