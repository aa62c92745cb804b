#include "performer/blink_generator.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace performer {

namespace {

// [0, 1) from the top 53 bits: the same on every platform, unlike std::uniform_real_distribution.
double uniform01(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

double next_interval(const BlinkParams& p, std::mt19937_64& engine) {
  // Inverse-CDF exponential; 1 - u lies in (0, 1], so the log is finite.
  return p.min_interval - (p.mean_interval - p.min_interval) * std::log(1.0 - uniform01(engine));
}

}  // namespace

std::vector<Blink> generate_blinks(const BlinkParams& p, double begin, double end) {
  if (!std::isfinite(begin) || !std::isfinite(end) || end < begin)
    throw std::invalid_argument("generate_blinks: need finite begin <= end");
  if (!(p.duration > 0.0) || !std::isfinite(p.duration)) throw std::invalid_argument("blink duration must be > 0");
  if (!(p.close_fraction > 0.0 && p.close_fraction < 1.0))
    throw std::invalid_argument("blink close_fraction must be in (0, 1)");
  if (!(p.min_interval >= p.duration) || !std::isfinite(p.min_interval))
    throw std::invalid_argument("blink min_interval must be at least the blink duration");
  if (!(p.mean_interval >= p.min_interval) || !std::isfinite(p.mean_interval))
    throw std::invalid_argument("blink mean_interval must be at least min_interval");
  std::mt19937_64 engine(p.seed);
  std::vector<Blink> blinks;
  double t = begin;
  while ((t += next_interval(p, engine)) < end) blinks.push_back({t, p.duration});
  return blinks;
}

double blink_weight(std::span<const Blink> blinks, double close_fraction, double t) {
  // The last blink starting at or before t is the only one that can cover t (intervals exceed
  // durations).
  const auto after =
      std::upper_bound(blinks.begin(), blinks.end(), t, [](double time, const Blink& b) { return time < b.start; });
  if (after == blinks.begin()) return 0.0;
  const Blink& b = *(after - 1);
  if (!(b.duration > 0.0) || t >= b.start + b.duration) return 0.0;
  const double x = (t - b.start) / b.duration;
  return x < close_fraction ? x / close_fraction : (1.0 - x) / (1.0 - close_fraction);
}

}  // namespace performer
