#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "codec/rate/hull.h"

namespace codec::rate {

// Where each code-block is truncated. A block's choice is always one of its hull points (or 0).
struct Selection {
  std::vector<int> passes;  // per block: coding passes included, 0 = none
  std::size_t bytes = 0;    // sum of the chosen hull points' bytes
  double distortion = 0;    // sum of the chosen hull points' weighted distortion decreases
};

// How many leading points of one block's hull have slope >= threshold. The slopes decrease, so
// these are exactly the points worth their bytes at that Lagrange multiplier.
std::size_t points_at_or_above(std::span<const HullPoint> hull, double threshold);

// The standard PCRD-opt selection: every block truncated after its last hull point with
// slope >= threshold. Lowering the threshold never removes a pass from any block.
// Throws std::invalid_argument for a NaN threshold.
Selection select(std::span<const std::vector<HullPoint>> hulls, double threshold);

// The selection that keeps points[b] leading hull points of block b (hulls.size() == points.size()
// and points[b] <= hulls[b].size(), unchecked). Bytes and distortion are summed in block order, so
// the same truncation gives bit-identical totals however it was found.
Selection selection_from_points(std::span<const std::vector<HullPoint>> hulls, std::span<const std::size_t> points);

}  // namespace codec::rate
