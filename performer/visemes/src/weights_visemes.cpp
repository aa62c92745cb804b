#include "performer/weights_visemes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace performer {

void check_viseme_sequence(std::span<const TimedViseme> sequence, int viseme_count) {
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const TimedViseme& v = sequence[i];
    const std::string at = "viseme sequence entry " + std::to_string(i) + ": ";
    if (!std::isfinite(v.start) || !std::isfinite(v.duration) || v.duration < 0.0)
      throw std::invalid_argument(at + "start and duration must be finite, duration non-negative");
    if (v.viseme < 0 || v.viseme >= viseme_count)
      throw std::invalid_argument(at + "viseme ID " + std::to_string(v.viseme) + " outside 0-" +
                                  std::to_string(viseme_count - 1));
    if (i > 0 && v.start < sequence[i - 1].start) throw std::invalid_argument(at + "starts before its predecessor");
  }
}

void check_weight_params(const WeightParams& p) {
  if (!(p.lead_in >= 0.0) || !std::isfinite(p.lead_in)) throw std::invalid_argument("lead_in must be >= 0");
  if (!(p.lambda > 0.0 && p.lambda <= 1.0)) throw std::invalid_argument("lambda must be in (0, 1]");
  if (!(p.time_scale > 0.0) || !std::isfinite(p.time_scale)) throw std::invalid_argument("time_scale must be > 0");
  if (p.max_visemes < 1) throw std::invalid_argument("max_visemes must be >= 1");
  if (!(p.contiguity >= 0.0) || !std::isfinite(p.contiguity)) throw std::invalid_argument("contiguity must be >= 0");
}

void keep_strongest(std::span<float> weights, int keep) {
  if (keep < 1) {
    std::fill(weights.begin(), weights.end(), 0.0f);
    return;
  }
  const std::size_t k = static_cast<std::size_t>(keep);
  if (weights.size() <= k) return;
  // Order: heavier first, lower index first among equals. Find the k-th entry of that order, then
  // zero everything after it. Channels number in the tens, so counting beats sorting a copy.
  const auto beats = [&](std::size_t a, std::size_t b) {
    return weights[a] > weights[b] || (weights[a] == weights[b] && a < b);
  };
  std::size_t last_kept = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    std::size_t better = 0;
    for (std::size_t j = 0; j < weights.size(); ++j) better += j != i && beats(j, i);
    if (better == k - 1) {
      last_kept = i;
      break;
    }
  }
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (i != last_kept && beats(last_kept, i)) weights[i] = 0.0f;
}

void viseme_weights_at(std::span<const TimedViseme> sequence, std::span<const DominanceWindow> windows,
                       const WeightParams& params, double t, std::span<float> out) {
  if (windows.size() != sequence.size()) throw std::invalid_argument("viseme_weights_at: one window per viseme");
  std::fill(out.begin(), out.end(), 0.0f);
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    const auto id = static_cast<std::size_t>(sequence[i].viseme);
    if (id >= out.size()) throw std::invalid_argument("viseme_weights_at: viseme ID beyond the output");
    out[id] += static_cast<float>(viseme_curve_weight(sequence[i], windows[i], params, t));
  }
  for (float& w : out) w = std::clamp(w, 0.0f, 1.0f);
  keep_strongest(out, params.max_visemes);
}

void viseme_weight_frames(std::span<const TimedViseme> sequence, const WeightParams& params,
                          std::span<const double> times, int viseme_count, std::span<float> out) {
  check_weight_params(params);
  check_viseme_sequence(sequence, viseme_count);
  const auto channels = static_cast<std::size_t>(viseme_count);
  if (out.size() != times.size() * channels)
    throw std::invalid_argument("viseme_weight_frames: output holds " + std::to_string(out.size()) +
                                " values, expected " + std::to_string(times.size() * channels));
  std::vector<DominanceWindow> windows(sequence.size());
  dominance_windows(sequence, params, windows);
  for (std::size_t f = 0; f < times.size(); ++f)
    viseme_weights_at(sequence, windows, params, times[f], out.subspan(f * channels, channels));
}

}  // namespace performer
