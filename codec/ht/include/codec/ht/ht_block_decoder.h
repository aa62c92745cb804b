#pragma once
#include <cstdint>
#include <span>
#include <stdexcept>

namespace codec::ht {

// A malformed HT code-block (a cleanup segment whose Scup does not fit, a magnitude exponent beyond
// what the decoder's 32-bit samples hold). The message names the problem; the caller adds where.
struct HtDecodeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What tier-2 gathered for one HT code-block (T.814 Annex B): the cleanup segment Dcup and the
// plane it codes down to, p = Mb - 1 - P (P the missing MSBs the packet header signalled).
struct HtCodewords {
  std::span<const std::uint8_t> cleanup;
  int cleanup_plane = 0;
};

// The most significant plane a decoded magnitude may reach: samples are kept, as the EBCOT decoder
// keeps them, as sign and twice the magnitude plus the reconstruction half-step, in 31 bits.
inline constexpr int kHtMaxMagnitudeBits = 30;

// Decodes the HT cleanup pass (T.814 clause 7: MEL, CxtVLC with the initial-row pair rule and
// U-VLC, MagSgn) of a w x h code-block (sizes as the encoder takes them) into `out` (w*h, row-major)
// in the representation the EBCOT decoder hands to dequantisation (codec/decoder block_decoder.h):
// each significant coefficient as its sign times (2 mu + 1) << p, mu the decoded magnitude at plane
// p, so that a lossless block (p = 0) reads 2|q| + 1; an insignificant one 0. An empty cleanup
// segment leaves the block 0. Throws HtDecodeError for a malformed segment (never reads outside
// it) and std::invalid_argument for a size outside 1..1024 with at most 4096 samples.
void decode_ht_block(const HtCodewords& block, int width, int height, std::span<std::int32_t> out);

}  // namespace codec::ht
