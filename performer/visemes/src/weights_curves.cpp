#include "performer/weights_curves.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace performer {

double exponential_weight(double t, double start, double duration, double lambda, double time_scale) {
  return lambda * std::exp(-std::abs(t - (start + 0.5 * duration)) / time_scale);
}

double ramp_weight(const DominanceWindow& w, double t) {
  if (t == w.peak) return 1.0;
  if (t <= w.rise_start || t >= w.fall_end) return 0.0;
  if (t < w.peak) return (t - w.rise_start) / (w.peak - w.rise_start);
  return (w.fall_end - t) / (w.fall_end - w.peak);
}

void dominance_windows(std::span<const TimedViseme> sequence, const WeightParams& params,
                       std::span<DominanceWindow> out) {
  const std::size_t n = sequence.size();
  const auto centre = [&](std::size_t i) { return sequence[i].start + 0.5 * sequence[i].duration; };
  double latest_end = -std::numeric_limits<double>::infinity();  // of the visemes before i
  for (std::size_t i = 0; i < n; ++i) {
    const TimedViseme& v = sequence[i];
    const bool touches_prev = i > 0 && sequence[i - 1].end() >= v.start - params.contiguity;
    const bool touches_next = i + 1 < n && v.end() >= sequence[i + 1].start - params.contiguity;
    // After silence there is nothing to coarticulate with: rise over the lead-in, but not back into
    // a viseme that is still being spoken.
    const double free_rise = std::max(v.start - params.lead_in, std::min(latest_end, v.start));
    DominanceWindow w;
    if (params.curve == WeightCurve::linear) {
      // Figure 3.8: peak at the start, zero at the end; rise while the predecessor falls.
      w = {touches_prev ? sequence[i - 1].start : free_rise, v.start, v.end()};
    } else {
      // Equation 3.8 peaks mid-viseme; neighbours share the stretch between their centres.
      w = {touches_prev ? centre(i - 1) : free_rise, centre(i), touches_next ? centre(i + 1) : v.end()};
    }
    // Overlapping input can put a neighbour's centre beyond this one's; keep the window ordered.
    w.rise_start = std::min(w.rise_start, w.peak);
    w.fall_end = std::max(w.fall_end, w.peak);
    out[i] = w;
    latest_end = std::max(latest_end, v.end());
  }
}

double viseme_curve_weight(const TimedViseme& viseme, const DominanceWindow& window, const WeightParams& params,
                           double t) {
  if (params.curve == WeightCurve::linear) return ramp_weight(window, t);
  // Half-open, so that where one window ends and the next begins only one of them counts.
  const bool inside = t == window.peak || (t >= window.rise_start && t < window.fall_end);
  return inside ? exponential_weight(t, viseme.start, viseme.duration, params.lambda, params.time_scale) : 0.0;
}

}  // namespace performer
