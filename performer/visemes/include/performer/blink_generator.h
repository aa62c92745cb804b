// The eye-action channel (thesis 3.4.5: "we add 1 more channel for eye action"; 3.3: "random
// generation of expression parameters for increased realism"): blinks at random intervals,
// reproducible from a seed.
//
// The intervals come from our own conversion of std::mt19937_64 output (whose sequence the C++
// standard fixes), not from std::exponential_distribution (whose algorithm each library chooses),
// so a seed gives the same blinks with every compiler.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace performer {

struct BlinkParams {
  std::uint64_t seed = 1;
  // Start-to-start interval: min_interval plus an exponential wait with mean
  // (mean_interval - min_interval). People blink about every 3-5 s at rest; the minimum keeps two
  // blinks from merging.
  double mean_interval = 4.0;
  double min_interval = 1.0;
  double duration = 0.25;       // lid closing plus opening, s
  double close_fraction = 0.4;  // the lid closes faster than it opens
};

struct Blink {
  double start = 0.0;
  double duration = 0.0;
};

// Blinks starting in [begin, end), in order; the first comes one interval after begin. Throws
// std::invalid_argument for non-finite or inverted bounds, duration <= 0, close_fraction outside
// (0, 1), min_interval < duration, or mean_interval < min_interval.
std::vector<Blink> generate_blinks(const BlinkParams& params, double begin, double end);

// The blink weight at t, for blinks in start order (as generated): a ramp up to 1 over close_fraction of a blink, back
// down over the rest; 0 between blinks.
double blink_weight(std::span<const Blink> blinks, double close_fraction, double t);

}  // namespace performer
