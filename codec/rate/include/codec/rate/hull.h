#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "codec/t1/block_encoder.h"

namespace codec::rate {

// A feasible truncation point of one code-block on the lower convex hull of its rate-distortion
// curve D(R), i.e. the upper concave hull of (bytes, distortion decrease). Only hull points are
// candidates for PCRD-opt: any other truncation point is beaten, for every Lagrange multiplier, by
// some hull point (EBCOT, section III-B).
struct HullPoint {
  int passes;         // coding passes included (1-based count: PassInfo index + 1)
  std::size_t bytes;  // cumulative codeword bytes to decode those passes (PassInfo::length)
  double distortion;  // cumulative weighted distortion decrease through those passes
  // Distortion gained per byte from the previous hull point (or from truncating at 0 passes, the
  // implicit origin (0 bytes, 0 distortion)). Positive and strictly decreasing along the hull, as
  // stored doubles, so callers may compare slopes exactly. +infinity only for a first point that
  // costs 0 bytes but gains distortion.
  double slope;
};

// The hull of one block's truncation points. `weight` turns PassInfo::distortion_decrease, measured
// on the integer coefficient grid, into image-domain distortion; the caller passes
// step^2 * synthesis-norm^2 * component weight, so slopes of different subbands become comparable.
// Passes that add bytes but no distortion (or lose distortion), and passes that lie above the hull,
// are skipped; collinear points are merged (only the farther one is kept), which keeps the slopes
// strictly decreasing. Truncation at 0 passes is implicit, not listed. No passes, or weight 0,
// gives an empty hull.
// Throws std::invalid_argument for a negative or non-finite weight, a non-finite distortion
// decrease, or pass lengths that decrease.
std::vector<HullPoint> convex_hull(std::span<const t1::PassInfo> passes, double weight);

}  // namespace codec::rate
