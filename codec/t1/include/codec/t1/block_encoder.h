#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/t1/block_style.h"

namespace codec::t1 {

// The subband a code-block belongs to; it selects the zero-coding contexts (T.800 Table D.1):
// LL and LH share them, HL uses them with horizontal and vertical swapped, HH has its own.
enum class Orientation { LL, HL, LH, HH };

struct PassInfo {
  // Bytes of the block's codeword needed to decode up to and including this pass: the shortest
  // valid truncation point (a decoder reading 0xFF past it decodes every pass so far correctly,
  // and one byte fewer would get a decision of these passes wrong, unless that falls below the
  // previous pass's length). For a pass that ends a codeword segment, the segment's end.
  // Non-decreasing from pass to pass, possibly equal (a pass whose decisions the decoder's 1-fill
  // already gets right adds no byte; the first pass may even need none); the last one equals
  // data.size().
  std::size_t length = 0;
  // Decrease of the squared error this pass buys, in units of the quantisation step squared,
  // assuming the decoder reconstructs a significant coefficient at the middle of its remaining
  // uncertainty interval. Without fractions (reversible coding) a coefficient is its index and is
  // known exactly once every bit-plane is; with them it is index + fraction, and a decoder that
  // has every plane places it at index + 1/2 (see encode_block).
  double distortion_decrease = 0.0;
  // Whether the MQ coder (or raw segment) was terminated after this pass.
  bool terminated = false;
};

struct EncodedBlock {
  std::vector<std::uint8_t> data;
  // Squared error with no pass decoded (the coefficients' energy), in the passes' units.
  double energy = 0.0;
  int missing_msbs = 0;  // zero bit-planes for the packet header: Mb minus the bit-planes coded
  int bit_planes = 0;    // magnitude bit-planes the coefficients use (the highest set bit, plus one)
  // Bit-planes the first pass codes: 1 for EBCOT, whose first pass is a cleanup of the most
  // significant plane; for an HT block (codec/ht), every plane from its most significant down to
  // the one its cleanup pass codes. The packet header's zero bit-planes are then
  // Mb - bit_planes + first_pass_planes - 1.
  int first_pass_planes = 1;
  std::vector<PassInfo> passes;
  // Whether a StopRule ended the coding before the last pass the coefficients have (the block's
  // bit-planes would give 3 * planes - 2).
  bool stopped_early = false;
};

// Where a rate-aware encoder may stop coding a block (DESIGN.md, "rate-aware tier-1"): after the
// cleanup pass that ends a bit-plane, once that bit-plane and the one before it each bought less
// than `min_slope` weighted distortion per byte (weight * distortion decrease / bytes, the bytes
// estimated from the coder's state), or that bit-plane alone where the block's slopes behave
// (a plane above it paid, this one bought something, the next brings no swell of new
// coefficients; or, before any plane paid, one that bought under a 32nd of the slope: block_encoder.cpp,
// stops_after_quiet_plane). The codeword is then terminated there, as if that pass
// were the last. A block whose weighted energy (all the distortion it could ever buy) is below `min_slope` times one
// byte is not coded at all: no pass, stopped_early set. 0: every pass. `pass_limit`, when positive, also stops the
// block (stopped_early set) after that many passes.
struct StopRule {
  double min_slope = 0;
  double weight = 1;
  int pass_limit = 0;
};

// Whether the passes measure the distortion decrease they buy (PassInfo::distortion_decrease).
// Rate control and the StopRule need it; an encode that keeps every pass (lossless, or lossy with
// no rate or quality target) does not, and skipping it takes some 6 % off tier-1. Skipped, every
// pass reports 0 (the energy is still given); the codeword is the same either way.
enum class Distortion { Measured, Skipped };

// Tier-1 (EBCOT) coding of one code-block, T.800 Annex D. `coefficients` holds width * height
// quantisation indices row by row, sign and magnitude, each magnitude below
// 2^magnitude_bitplanes (Mb, at most 31). Any width and height >= 1 are accepted (edge blocks).
// The first pass is a cleanup pass on the most significant non-zero bit-plane, then
// significance propagation, magnitude refinement and cleanup on each plane below: 3 * planes - 2
// passes. An all-zero block yields no passes, no data and missing_msbs = Mb.
// `fractions`, for irreversible coding: per coefficient, floor(256 * (|c| / step - index)), the
// part of the coefficient the index drops. It changes no bit of the codeword, only the distortion
// each pass reports, which then measures the error against the coefficient itself with the
// final reconstruction at index + 1/2 (as OpenJPEG and Kakadu decode irreversible bands), rather
// than against the index. Empty: the index is the coefficient (reversible coding).
// Throws std::invalid_argument for inconsistent arguments.
EncodedBlock encode_block(std::span<const std::int32_t> coefficients, int width, int height, Orientation o,
                          int magnitude_bitplanes, BlockStyle style, std::span<const std::uint8_t> fractions = {},
                          StopRule stop = {});

// A code-block still inside its subband's plane: `origin` is its first coefficient, rows lie
// `stride` elements apart. Integer: quantisation indices (or reversible coefficients) as they are.
struct IntegerBlock {
  const std::int32_t* origin = nullptr;
  std::ptrdiff_t stride = 0;
  int width = 0, height = 0;
};

// Float wavelet coefficients, quantised as they are loaded with 1 / step (dead_zone.h), their
// fractions kept for the distortion figures: the same codeword and figures as quantising the plane
// first and calling encode_block with the indices and fractions, without those planes.
struct FloatBlock {
  const float* origin = nullptr;
  std::ptrdiff_t stride = 0;
  int width = 0, height = 0;
  float inverse_step = 1;
};

// What the largest coefficient of a float block decides: the bit-planes its indices use, and the
// fraction bits its fixed-point magnitudes keep (as many of 8 as stay below 2^31).
struct FloatBlockPlanes {
  int bit_planes = 0;
  int fine_bits = 0;
};
// A float block's bit-planes and energy (the sum of its scaled magnitudes' squares, each cut to
// 1/256ths of an index, as the coders measure distortion), reading it once and loading nothing (a
// second time only for a block of more than 23 planes). At low rates most blocks are worth no pass:
// EBCOT's stop rule and HT rate control tell them by this before loading them.
struct FloatBlockSurvey {
  FloatBlockPlanes planes;
  double energy = 0;
};
FloatBlockSurvey survey_float_block(const FloatBlock& block);

// encode_block on a block in place. Mb may be 31 when the caller learns the bit-planes from the
// result (EncodedBlock::bit_planes) and sets missing_msbs itself.
// A StopRule needs the distortion: Skipped with a stop rule is an error.
EncodedBlock encode_block(const IntegerBlock& block, Orientation o, int magnitude_bitplanes, BlockStyle style,
                          StopRule stop = {}, Distortion distortion = Distortion::Measured);
EncodedBlock encode_block(const FloatBlock& block, Orientation o, int magnitude_bitplanes, BlockStyle style,
                          StopRule stop = {}, Distortion distortion = Distortion::Measured);

}  // namespace codec::t1
