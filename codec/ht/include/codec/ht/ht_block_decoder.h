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

// What tier-2 gathered for one HT set of a code-block (T.814 Annex B): the cleanup segment Dcup and
// the plane it codes down to, p = Mb - 1 - P (P the missing MSBs the packet header signalled, plus
// one per placeholder set before it); then the refinement segment Dref with how many of its passes
// arrived: 0, 1 (SigProp) or 2 (SigProp and MagRef), both on plane p - 1.
struct HtCodewords {
  std::span<const std::uint8_t> cleanup;
  int cleanup_plane = 0;
  std::span<const std::uint8_t> refinement;
  int refinement_passes = 0;
  bool vertically_causal = false;  // code-block style 0x08: SigProp ignores the stripe below
};

// The most significant plane a decoded magnitude may reach: samples are kept, as the EBCOT decoder
// keeps them, as sign and twice the magnitude plus the reconstruction half-step, in 31 bits.
inline constexpr int kHtMaxMagnitudeBits = 30;

// Decodes one HT set of a w x h code-block (sizes as the encoder takes them): the cleanup pass
// (T.814 7.3: MEL, CxtVLC with the initial-row pair rule and U-VLC, MagSgn), then the SigProp (7.4)
// and MagRef (7.5) passes that arrived. Writes `out` (w*h, row-major) in the representation the
// EBCOT decoder hands to dequantisation (codec/decoder block_decoder.h): sign times twice the
// magnitude reconstructed at the middle of what the passes leave open. After the cleanup alone a
// significant coefficient reads (2 mu + 1) << p, mu its magnitude at plane p, so a lossless block
// (p = 0) reads 2|q| + 1; after MagRef, (2 (2 mu + bit) + 1) << (p - 1); one that SigProp finds
// significant, 3 << (p - 1); an insignificant one 0. An empty cleanup segment leaves the block 0.
// Throws HtDecodeError for a malformed set (never reads outside its segments) and
// std::invalid_argument for a size outside 1..1024 with at most 4096 samples.
void decode_ht_block(const HtCodewords& block, int width, int height, std::span<std::int32_t> out);

}  // namespace codec::ht
