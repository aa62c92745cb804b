#include "codec/rate/hull.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace codec::rate {

namespace {

void validate(std::span<const t1::PassInfo> passes, double weight) {
  if (!std::isfinite(weight) || weight < 0.0)
    throw std::invalid_argument("hull weight must be finite and >= 0, got " + std::to_string(weight));
  std::size_t previous_length = 0;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    if (!std::isfinite(passes[i].distortion_decrease))
      throw std::invalid_argument("pass " + std::to_string(i) + " has a non-finite distortion decrease");
    if (passes[i].length < previous_length)
      throw std::invalid_argument("pass lengths must be non-decreasing; pass " + std::to_string(i) + " has " +
                                  std::to_string(passes[i].length) + " bytes after " + std::to_string(previous_length));
    previous_length = passes[i].length;
  }
}

// A point of the (bytes, distortion) plane; the hull's last point or the implicit origin.
struct Corner {
  std::size_t bytes;
  double distortion;
};

Corner last_corner(const std::vector<HullPoint>& hull) {
  if (hull.empty()) return Corner{0, 0.0};
  return Corner{hull.back().bytes, hull.back().distortion};
}

// Distortion gained per byte from `from` to (bytes, distortion), which gains some. A step that
// costs no bytes is free, so it must rank before every finite slope: +infinity, rather than a
// division by zero.
double slope_from(Corner from, std::size_t bytes, double distortion) {
  if (bytes == from.bytes) return std::numeric_limits<double>::infinity();
  return (distortion - from.distortion) / static_cast<double>(bytes - from.bytes);
}

}  // namespace

std::vector<HullPoint> convex_hull(std::span<const t1::PassInfo> passes, double weight) {
  validate(passes, weight);
  std::vector<HullPoint> hull;
  // Summed unweighted, then weighted once per point, so a point's distortion is exactly
  // weight * (sum of the decreases through its pass) whatever happened before it.
  double decrease = 0.0;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    decrease += passes[i].distortion_decrease;
    const double distortion = weight * decrease;
    const std::size_t bytes = passes[i].length;
    // Lengths only grow, so a point no better than the hull's end is dominated by it now and
    // by whatever replaces that end later: it can never be a hull vertex.
    if (distortion <= last_corner(hull).distortion) continue;
    // Monotone-chain scan (points arrive in order of bytes): a hull end that the new point sees
    // at an equal or steeper slope lies on or under the chord that skips it, so it goes. The
    // comparison is on the stored quotients themselves, so the kept slopes are strictly
    // decreasing as doubles, not just mathematically.
    double slope = slope_from(last_corner(hull), bytes, distortion);
    while (!hull.empty() && slope >= hull.back().slope) {
      hull.pop_back();
      slope = slope_from(last_corner(hull), bytes, distortion);
    }
    hull.push_back(HullPoint{static_cast<int>(i + 1), bytes, distortion, slope});
  }
  return hull;
}

}  // namespace codec::rate
