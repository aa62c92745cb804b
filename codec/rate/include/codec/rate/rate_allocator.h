#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/rate/hull.h"
#include "codec/rate/selection.h"

namespace codec::rate {

// PCRD-opt over many code-blocks, prepared once so each query is cheap (the encoder asks ~20
// budgets per image while it converges on the header overhead).
//
// Every hull step (block b going from hull point j-1 to j) is sorted once by decreasing slope,
// ties by block index and then by step. Because each block's slopes strictly decrease, any prefix
// of that order takes each block's steps in order, and the threshold selections are exactly the
// prefixes that end between two different slopes. So instead of bisecting on the threshold, a
// budget maps to the longest prefix whose byte sum fits (a binary search over prefix sums) - the
// limit bisection converges to, except that it can also split a group of equal slopes.
// The room that prefix leaves is then filled greedily: the remaining steps in slope order, each
// taken when it is its block's next step and still fits.
//
// The allocator refers to `hulls` (one per code-block, as convex_hull returns them) without
// copying them; they must outlive it, unchanged.
class RateAllocator {
 public:
  // Throws std::invalid_argument for a hull that is not one: pass counts not increasing, bytes
  // decreasing, or slopes that are not positive and strictly decreasing.
  explicit RateAllocator(std::span<const std::vector<HullPoint>> hulls);

  std::size_t block_count() const { return hulls_.size(); }
  // Bytes and distortion of every block kept whole (to its last hull point).
  std::size_t total_bytes() const { return prefix_bytes_.back(); }
  double total_distortion() const { return prefix_distortion_.back(); }

  // The standard PCRD-opt selection: each block through its last hull point with slope >= threshold.
  // Same result as select(hulls, threshold). Throws std::invalid_argument for a NaN threshold.
  Selection for_threshold(double threshold) const;

  // The longest slope-ordered prefix that fits in `budget` bytes, completed greedily (see above).
  // Never exceeds the budget; its bytes never decrease as the budget grows. When the budget is the
  // byte count of some threshold selection, the result is that selection, which is optimal at its
  // rate; otherwise it is within the distortion of one hull step (the first one left out of the
  // prefix) of the best truncation that fits.
  Selection for_budget(std::size_t budget) const;

  // The shortest slope-ordered prefix whose remaining distortion,
  // total_weighted_energy - distortion, is <= max_distortion (up to floating-point rounding of the
  // sums); no threshold selection meeting the target has fewer bytes. If even every pass of every
  // block leaves more, all of them. Throws std::invalid_argument for NaN arguments.
  Selection for_distortion(double total_weighted_energy, double max_distortion) const;

  // Quality layers for non-decreasing byte budgets: per layer, the cumulative passes of every block.
  // Layer 0 is for_budget(budgets[0]); each later layer starts from the one before (pass counts
  // never go down) and spends its extra room the same way, prefix order first, greedily. Each
  // layer's blocks total at most its budget. Throws std::invalid_argument for decreasing budgets.
  std::vector<std::vector<int>> layers(std::span<const std::size_t> budgets) const;

 private:
  struct Step {
    std::uint32_t block;
    std::uint32_t point;  // index in the block's hull of the point this step reaches
    std::size_t bytes;    // bytes the step adds
  };

  // Construction, in order: per-block offsets (validating each hull), the slope order, its sums.
  void index_blocks();
  void order_steps();
  void accumulate();
  // Per block, how many hull points the first `prefix` steps of order_ include.
  std::vector<std::size_t> points_in_prefix(std::size_t prefix) const;
  // Walks order_ from `from`, adding each step that is its block's next and fits in `room` bytes.
  void complete_greedily(std::vector<std::size_t>& points, std::size_t& room, std::size_t from) const;

  std::span<const std::vector<HullPoint>> hulls_;
  std::vector<Step> order_;                    // every hull step, by decreasing slope
  std::vector<std::size_t> prefix_bytes_;      // [k] = bytes of order_[0..k); size order_.size() + 1
  std::vector<double> prefix_distortion_;      // [k] = distortion of order_[0..k)
  std::vector<std::size_t> suffix_min_bytes_;  // [k] = fewest bytes of any step in order_[k..]
  std::vector<std::size_t> first_step_;        // block b's steps are rank_[first_step_[b] .. first_step_[b+1])
  std::vector<std::uint32_t> rank_;            // position in order_ of each block's steps, increasing
};

}  // namespace codec::rate
