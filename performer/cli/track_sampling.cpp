#include "track_sampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace performer::cli {

void sample_track(const WeightTrack& track, double seconds, std::span<float> out) {
  const std::vector<double>& t = track.times;
  const std::size_t channels = track.channel_count();
  if (t.empty()) {
    std::fill(out.begin(), out.end(), 0.0f);
    return;
  }
  const auto after = std::upper_bound(t.begin(), t.end(), seconds);
  if (after == t.begin() || after == t.end()) {
    const auto row = track.frame(after == t.begin() ? 0 : t.size() - 1);
    std::copy(row.begin(), row.end(), out.begin());
    return;
  }
  const auto f1 = static_cast<std::size_t>(after - t.begin());
  const std::size_t f0 = f1 - 1;
  const double span = t[f1] - t[f0];
  const auto a = static_cast<float>(span > 0.0 ? (seconds - t[f0]) / span : 0.0);
  const auto r0 = track.frame(f0), r1 = track.frame(f1);
  for (std::size_t c = 0; c < channels; ++c) out[c] = r0[c] + a * (r1[c] - r0[c]);
}

void keep_strongest(std::span<float> weights, int count) {
  std::vector<std::size_t> acting;
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (weights[i] != 0.0f) acting.push_back(i);
  if (static_cast<int>(acting.size()) <= count) return;
  std::stable_sort(acting.begin(), acting.end(),
                   [&](std::size_t a, std::size_t b) { return std::abs(weights[a]) > std::abs(weights[b]); });
  for (std::size_t k = static_cast<std::size_t>(std::max(count, 0)); k < acting.size(); ++k) weights[acting[k]] = 0.0f;
}

}  // namespace performer::cli
