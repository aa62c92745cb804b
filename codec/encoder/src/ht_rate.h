#pragma once
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "codec/encoder/params.h"
#include "rate_control.h"
#include "tile_coder.h"
#include "base/thread_pool.h"

namespace codec {

// Rate control for HT code-blocks (README, "HT rate control"). An HT block's truncation points are
// cleanups coded from different bit-planes (ht_candidates.h), each a codeword of its own, so
// coding them all would cost a cleanup per plane. Instead, as EBCOT's pass skipping does, a
// sample of the blocks is coded around and below where a first estimate cuts them and predicts the
// final slope threshold; every other block then gets its cleanups' distortions (float sums of
// their definitions) and lengths estimated, the lengths from counts of significant quads and
// magnitude bits (ht::plane_statistics, scaled by what the sample's cleanups really took; a block
// whose energy alone is worth too little is skipped on a survey, without being loaded), and
// only the cleanups from the plane that estimate picks at the threshold, the plane above it
// unless the estimate takes the picked plane by a wide margin, and, where the estimate comes near
// taking it, the plane below are coded. After the allocation, blocks whose choice lies at the edge
// of what was coded get the next planes coded (ht_blocks_at_edges) and the allocation is redone.

// Tier-1 of a tile's HT blocks under a target: fills coded.ht_candidates, and coded.blocks with
// their truncation points. With no target to predict from (or few blocks) every block gets every
// plane. `block_done` is called once per block, from any worker thread.
void code_ht_candidates(CodedTile& coded, const EncodeParams& params, const Tier1Target& target, base::ThreadPool& pool,
                        const std::function<void()>& block_done);

// Where the base step's octave should begin for an HT byte target (README, "The step's phase"):
// log2(S / base step), S the one step at which a uniform quantiser (every block's cleanup on the
// same plane) would spend the target, as the length model at its nominal scale tells it from the
// plane counts of a part of many blocks (ht_rate.cpp, kPhaseRows). Empty when even plane 0
// spends less. `coded` holds the tile's jobs at
// the base step, its coefficients transformed.
std::optional<double> ht_uniform_step_octaves(const CodedTile& coded, const EncodeParams& params,
                                              const Tier1Target& target, base::ThreadPool& pool);

// A block whose allocation might change with more planes coded, and those planes.
struct HtExtension {
  std::size_t tile = 0, block = 0;
  std::vector<int> planes;
};

// The blocks of an allocation (`passes`, rate_control.h) that may be cut short by what was coded:
// one whose choice is the highest cleanup coded alone (or nothing) while higher planes are uncoded
// (a cleanup from higher up might be worth its bytes at the threshold where this one is not)
// unless the plane above was left out by a margin that still holds at `lowest_slope`, one whose
// choice is the lowest cleanup coded above plane 0 (or its refinement), and one skipped whose
// slope bound (HtCandidates::slope_bound) reaches `lowest_slope` (the lowest slope the allocation
// takes). A skipped block whose bound came from its energy alone (HtCandidates::bound_from_energy)
// is loaded and bounded from its plane statistics first, and that bound replaces it.
std::vector<HtExtension> ht_blocks_at_edges(std::vector<CodedTile>& tiles, const LayerPasses& passes,
                                            double lowest_slope, const EncodeParams& params, base::ThreadPool& pool);

// Codes the extensions' planes (in parallel on `pool`) and updates the blocks' truncation points.
void extend_ht_candidates(std::vector<CodedTile>& tiles, const std::vector<HtExtension>& extensions,
                          const EncodeParams& params, base::ThreadPool& pool);

// Before measuring trial files: every coded cleanup's missing_msbs from its block's settled Mb.
void sync_ht_missing_msbs(std::vector<CodedTile>& tiles, base::ThreadPool& pool);

// After the allocation: each block's chosen point takes the place of its truncation points, as
// its codeword cut after the chosen pass (the cleanup, and SigProp and MagRef if chosen) in the
// first layer that has any (T.814: an HT code-block's one cleanup and refinement segment), and the
// candidates are dropped. The tiles then look as if tier-1 had coded that cleanup alone. Block by
// block in parallel on `pool`.
void settle_ht_choices(std::vector<CodedTile>& tiles, LayerPasses& passes, base::ThreadPool& pool);

// Tier-2's view of one block while candidates are open: the cleanup a truncation after
// `cumulative_passes` (per layer) points stands for; its passes in each layer that has any are
// written to `passes_out` (one per layer).
const t1::EncodedBlock& ht_packet_plan(const CodedTile& coded, std::size_t block,
                                       std::span<const int> cumulative_passes, std::span<int> passes_out);

}  // namespace codec
