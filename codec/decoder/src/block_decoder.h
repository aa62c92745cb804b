#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/structure/tile.h"
#include "codec/t1/block_style.h"

namespace codec::dec {

// One codeword segment of a code-block (T.800 D.4, B.10.7.2): `passes` coding passes carried in
// `bytes` bytes, terminated at its end.
struct Segment {
  std::size_t bytes = 0;
  int passes = 0;
};

// What tier-2 gathered for one code-block.
struct BlockCodewords {
  std::span<const std::uint8_t> data;  // the segments' bytes, back to back
  std::span<const Segment> segments;
  int passes = 0;      // sum of the segments' passes
  int top_plane = -1;  // bit-plane of the first (cleanup) pass: Mb - P - 1 (+ ROI shift)
};

// The most significant bit-plane a block may start at: the decoder keeps each magnitude, with
// its reconstruction half-step, in 31 bits (3 * 2^plane at most); in 63 for the int64 form, which
// blocks deeper than that need (samples of more than 31 bits, T.800's 38 with the transform's
// growth and guard bits, or large ROI shifts).
inline constexpr int kMaxTopPlane = 29;
inline constexpr int kMaxWideTopPlane = 61;

// EBCOT tier-1 decoding (T.800 Annex D, every code-block style switch) of a w x h code-block of
// band `orientation`. Writes `out` (w*h, row-major): each coefficient as sign and twice its
// magnitude reconstructed at the middle of the interval the decoded bit-planes leave open (r = 1/2,
// E.1.1.2); an insignificant coefficient is 0. So a coefficient decoded through bit-plane 0 reads
// 2|q|+1, and one decoded down to plane p reads (2|q>>p|+1) << p.
void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                       const t1::BlockStyle& style, std::span<std::int32_t> out);
// The same with int64 coefficients, for blocks of up to kMaxWideTopPlane + 1 bit-planes.
void decode_code_block(const BlockCodewords& block, int width, int height, BandOrientation orientation,
                       const t1::BlockStyle& style, std::span<std::int64_t> out);

}  // namespace codec::dec
