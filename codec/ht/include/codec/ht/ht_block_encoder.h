#pragma once
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "codec/t1/block_encoder.h"

namespace codec::ht {

// HT block coding (ITU-T T.814 | ISO/IEC 15444-15, the FBCOT block coder) of one code-block,
// behind the same seam as EBCOT (DESIGN.md, "Two block coders behind one seam"): it returns the
// same EncodedBlock, so rate control, tier-2 and the codestream writer need not know which coder
// ran beyond the CAP marker and the code-block style bit.
//
// The block is coded by one HT cleanup pass on bit-plane `cleanup_plane` (p): every sample's
// magnitude with its p lowest bits dropped, all its remaining bits at once (quads, MEL, CxtVLC,
// U-VLC and MagSgn; T.814 clause 7). p = 0 codes the indices exactly (lossless). The result has one
// pass, terminated, whose length is the whole cleanup segment; `first_pass_planes` is the planes
// it codes (bit_planes - p), so missing_msbs = Mb - 1 - p, which is how the packet header tells a
// decoder the cleanup's plane. A block with no magnitude at or above 2^p has no pass and
// missing_msbs = Mb. The distortion decrease assumes mid-point reconstruction, in EncodedBlock's
// units (EBCOT's encode_block).
//
// `coefficients`: width * height quantisation indices, row by row, each magnitude below
// 2^magnitude_bitplanes (Mb, at most 31); `fractions` as for encode_block (irreversible coding),
// or empty. Sizes 1..1024 with width * height <= 4096. Throws std::invalid_argument otherwise.
t1::EncodedBlock encode_ht_block(std::span<const std::int32_t> coefficients, int width, int height,
                                 int magnitude_bitplanes, int cleanup_plane = 0,
                                 std::span<const std::uint8_t> fractions = {},
                                 t1::Distortion distortion = t1::Distortion::Measured);

// The same on a block in place, as encode_block takes it (a float block is quantised as loaded).
t1::EncodedBlock encode_ht_block(const t1::IntegerBlock& block, int magnitude_bitplanes, int cleanup_plane = 0,
                                 t1::Distortion distortion = t1::Distortion::Measured);
t1::EncodedBlock encode_ht_block(const t1::FloatBlock& block, int magnitude_bitplanes, int cleanup_plane = 0,
                                 t1::Distortion distortion = t1::Distortion::Measured);

// A code-block loaded once for coding from several cleanup planes (rate control's candidates):
// magnitudes and signs row by row, and for irreversible coding the fractions the indices drop.
struct HtBlock {
  int width = 0, height = 0;
  std::vector<std::uint32_t> magnitudes;
  std::vector<std::uint8_t> negative;   // non-zero: negative (a zero index's sign where signs_of_zeros)
  std::vector<std::uint8_t> fractions;  // empty: reversible
  int bit_planes = 0;                   // the highest set bit of any magnitude, plus one
  // Per sample, the bit length L of its magnitude and T of its magnitude without the top bit: its
  // exponent at any cleanup plane p follows from them (T.814 7.3.7: L - p + [T > p] where L > p),
  // so each candidate cleanup needs no bit scan of its own.
  std::vector<std::uint8_t> lengths, lengths_below_top;
  // No less than the block's energy (the sum of (magnitude + fraction / 256)^2), known from the load
  // at no cost: for a float block the sum of its scaled coefficients' squares (each at least its
  // index and fraction), in float with a margin over its rounding; for an integer block infinity.
  double energy_bound = std::numeric_limits<double>::infinity();
  // Whether `negative` holds the coefficient's sign for indices of 0 too (a float load's): then a
  // sample just under the cleanup plane may be coded as significant (ht_block_encoder.cpp,
  // "Raising near-significant samples").
  bool signs_of_zeros = false;
};

HtBlock load_ht_block(std::span<const std::int32_t> coefficients, int width, int height,
                      std::span<const std::uint8_t> fractions = {});
HtBlock load_ht_block(const t1::IntegerBlock& block);
HtBlock load_ht_block(const t1::FloatBlock& block);
// The same into a block kept from an earlier load (a worker's, reused): its buffers are resized,
// not made anew, so a block of the same size costs no allocation and no clearing.
void load_ht_block(const t1::IntegerBlock& block, HtBlock& into);
void load_ht_block(const t1::FloatBlock& block, HtBlock& into);

// Which passes an HT block gets: the cleanup alone, or the cleanup followed by the SigProp and
// MagRef passes of the plane below it (T.814 7.4, 7.5).
enum class HtPasses { Cleanup, CleanupAndRefinement };

// encode_ht_block on a loaded block. With HtPasses::CleanupAndRefinement, a cleanup on plane p >= 1
// that has a pass is followed by passes 2 and 3: SigProp and MagRef of plane p - 1, in one more
// codeword segment (the HT refinement segment: SigProp bytes forwards, then MagRef bytes, which
// the decoder reads backwards from the segment's end). Pass lengths are cumulative as ever, so a
// truncation after SigProp is a prefix of the three; each pass's distortion decrease is exact
// with mid-point reconstruction (a sample SigProp makes significant at 1.5 * 2^(p-1), one MagRef
// refines at the middle of its halved interval). A SigProp pass with no bit to send adds no byte.
t1::EncodedBlock encode_ht_block(const HtBlock& block, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion = t1::Distortion::Measured,
                                 HtPasses passes = HtPasses::Cleanup);

// What a cleanup from bit-plane p leaves and what it costs, known without coding it: the squared
// error a decoder is left with (mid-point reconstruction, in EncodedBlock's units), and the counts
// the cleanup's length follows (T.814 7.3: a quad with no significant sample costs a MEL symbol at
// most; a significant one a CxtVLC codeword and a U-VLC residual; each significant sample about
// U_q MagSgn bits, U_q the bit length of the quad's largest magnitude at that plane).
struct PlaneStatistics {
  double error = 0;  // an estimate within 1e-5 of the energy, which (the last entry's) is exact
  double significant_quads = 0;
  double significant_samples = 0;
  double magnitude_bits = 0;  // the sum over significant samples of their quad's magnitude bit length
};

// One entry per plane p = 0 .. bit_planes - 1, then one for nothing coded (error: the block's
// energy, counts 0). Linear in the samples times the bit-planes they use.
std::vector<PlaneStatistics> plane_statistics(const HtBlock& block);

// The same in two steps, for a caller that learns from the counts which planes it needs errors
// for: plane_counts gives the counts (errors 0); add_plane_errors then fills in the errors of the
// planes from `lowest_plane` up (the energy always), and gives each plane below it the error of
// `lowest_plane` (as if it bought nothing more: such a point is dominated, never on a hull).
std::vector<PlaneStatistics> plane_counts(const HtBlock& block);
void add_plane_errors(const HtBlock& block, std::vector<PlaneStatistics>& statistics, int lowest_plane);

}  // namespace codec::ht
