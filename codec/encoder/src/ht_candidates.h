#pragma once
#include <optional>
#include <span>
#include <vector>

#include "codec/ht/ht_block_encoder.h"
#include "codec/t1/block_encoder.h"

namespace codec {

// One HT code-block's truncation points under a byte or PSNR target (README, "HT rate control").
// An HT cleanup pass codes every plane from the block's most significant one down to the plane it
// starts at (T.814 clause 7), so, unlike EBCOT's passes, a lower truncation point is not a longer
// prefix of one codeword but another codeword: the cleanup coded from another plane. Each such
// codeword also carries the SigProp and MagRef passes of the plane below its cleanup, which are
// prefixes of it: cleanup p, cleanup p + SigProp p-1, cleanup p + SigProp + MagRef p-1. Rate
// control sees all of these as the block's passes, from the highest plane down (pass k: the k-th
// point), lengths being each point's own bytes and distortion decreases the differences between
// their errors; the hull and the allocator then work as for EBCOT. One is chosen per block and
// replaces them (settle_ht_choices), as one codeword in one quality layer.
struct HtPoint {
  int plane = 0;   // the cleanup's plane
  int passes = 1;  // of that codeword: 1 the cleanup alone, 2 with SigProp, 3 with SigProp and MagRef
};

struct HtCandidates {
  std::vector<std::optional<t1::EncodedBlock>> by_plane;  // [p]: the codeword from plane p, once coded
  std::vector<HtPoint> points;                            // each truncation point rate control sees, highest first
  bool skipped = false;  // not coded at all: its energy was worth too little (see ht_rate.h)
  // Skipped blocks: an upper bound of the slope any of its points could have (ht_rate.cpp's
  // slope_bound), against which rate control checks whether skipping it was too soon.
  double slope_bound = 0;
  // Whether slope_bound is the looser bound from the block's energy alone (a block skipped without
  // being loaded, ht_rate.cpp): the check loads it and bounds it as slope_bound does before coding it.
  bool bound_from_energy = false;
  // Where the cleanup above the estimated plane was left uncoded (ht_rate.cpp, kAboveReach): that
  // plane, and the estimated slope of its cleanup's step from the hull point above it; -1 and 0
  // where it was not.
  int above_left_plane = -1;
  double above_left_slope = 0;
  // Whether only the top planes were coded because the estimate took nothing of the block at the
  // threshold (or it was skipped, and extended since): should the allocation take it after all,
  // the estimate was off for it, and it is estimated again where the allocation reached
  // (ht_blocks_at_edges), once (estimated_again).
  bool estimated_nothing = false;
  bool estimated_again = false;

  int highest_coded() const;  // -1: none coded
  int lowest_coded() const;   // -1: none coded
  // The point a truncation after `passes` of the block's truncation points stands for, and its codeword.
  const HtPoint& point(int passes) const { return points[static_cast<std::size_t>(passes) - 1]; }
  const t1::EncodedBlock& chosen(int passes) const { return *by_plane[static_cast<std::size_t>(point(passes).plane)]; }
};

// Codes the cleanups from `planes` (each below block.bit_planes) that are not coded yet, each with
// its refinement passes, with Mb = 31 (missing_msbs is set later, sync_missing_msbs).
void add_candidates(HtCandidates& candidates, const ht::HtBlock& block, std::span<const int> planes,
                    ht::HtPasses passes = ht::HtPasses::CleanupAndRefinement);

// The block as rate control sees it: bit_planes and energy from the block, and one pass per
// point of the coded codewords, highest plane first, with each point's length and the distortion
// it buys over the previous one. A point that takes no more bytes than one before it leaves that
// one dominated: it is dropped (`points` says which remain); so is a refinement pass that adds no
// byte to its cleanup (a SigProp pass with nothing to send: a decoder would see an empty
// segment). Its missing_msbs is the block's, counted as for a cleanup of its top plane
// (first_pass_planes 1).
t1::EncodedBlock truncation_points(HtCandidates& candidates, int bit_planes, double energy);

// Sets each coded cleanup's missing_msbs from the block's (truncation_points' convention, after
// the encoder has settled Mb): Mb - 1 - p for the cleanup from plane p.
void sync_missing_msbs(HtCandidates& candidates, const t1::EncodedBlock& points);

// The EBCOT pass count whose decode leaves each coefficient known to the same planes as the
// point a truncation after `passes` points stands for (a cleanup from plane p reconstructs as
// EBCOT's cleanup pass of plane p, and HT's SigProp and MagRef as EBCOT's, which code the same
// samples in the same order): for t1::reconstruct. 0 for 0.
int ebcot_equivalent_passes(const HtCandidates& candidates, int bit_planes, int passes);

}  // namespace codec
