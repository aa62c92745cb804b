#include "codec/rate/selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace codec::rate {

std::size_t points_at_or_above(std::span<const HullPoint> hull, double threshold) {
  const auto end =
      std::partition_point(hull.begin(), hull.end(), [threshold](const HullPoint& p) { return p.slope >= threshold; });
  return static_cast<std::size_t>(end - hull.begin());
}

Selection select(std::span<const std::vector<HullPoint>> hulls, double threshold) {
  // A NaN compares false with every slope and would silently select nothing.
  if (std::isnan(threshold)) throw std::invalid_argument("PCRD threshold is NaN");
  std::vector<std::size_t> points(hulls.size());
  for (std::size_t b = 0; b < hulls.size(); ++b) points[b] = points_at_or_above(hulls[b], threshold);
  return selection_from_points(hulls, points);
}

Selection selection_from_points(std::span<const std::vector<HullPoint>> hulls, std::span<const std::size_t> points) {
  Selection s;
  s.passes.resize(hulls.size(), 0);
  for (std::size_t b = 0; b < hulls.size(); ++b) {
    if (points[b] == 0) continue;
    const HullPoint& last = hulls[b][points[b] - 1];
    s.passes[b] = last.passes;
    s.bytes += last.bytes;
    s.distortion += last.distortion;
  }
  return s;
}

}  // namespace codec::rate
