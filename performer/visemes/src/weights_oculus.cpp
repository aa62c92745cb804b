#include "performer/weights_oculus.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace performer {

namespace {

std::size_t oculus_index(std::string_view name) {
  const auto it = std::find(kOculusVisemes.begin(), kOculusVisemes.end(), name);
  if (it == kOculusVisemes.end()) throw std::invalid_argument("'" + std::string(name) + "' is not an Oculus viseme");
  return static_cast<std::size_t>(it - kOculusVisemes.begin());
}

}  // namespace

void fold_to_oculus(std::span<const float> weights, const VisemeSet& set, std::span<float> out) {
  if (weights.size() != static_cast<std::size_t>(set.size()) || out.size() != kOculusVisemes.size())
    throw std::invalid_argument("fold_to_oculus: one weight per viseme in, 15 out");
  std::fill(out.begin(), out.end(), 0.0f);
  for (std::size_t i = 0; i < weights.size(); ++i) out[oculus_index(set.visemes[i].oculus)] += weights[i];
  for (float& w : out) w = std::min(w, 1.0f);
}

WeightTrack oculus_track(const WeightTrack& track, const VisemeSet& set) {
  if (track.viseme_channels != set.size()) throw std::invalid_argument("oculus_track: track and set disagree");
  WeightTrack out;
  out.fps = track.fps;
  out.times = track.times;
  out.channels.assign(kOculusVisemes.begin(), kOculusVisemes.end());
  out.viseme_channels = static_cast<int>(kOculusVisemes.size());
  const auto old_visemes = static_cast<std::size_t>(track.viseme_channels);
  out.channels.insert(out.channels.end(), track.channels.begin() + track.viseme_channels, track.channels.end());
  const std::size_t width = out.channels.size();
  out.values.assign(out.times.size() * width, 0.0f);
  for (std::size_t f = 0; f < track.frame_count(); ++f) {
    const std::span<const float> in = track.frame(f);
    const std::span<float> row = std::span<float>(out.values).subspan(f * width, width);
    fold_to_oculus(in.first(old_visemes), set, row.first(kOculusVisemes.size()));
    std::copy(in.begin() + track.viseme_channels, in.end(), row.begin() + out.viseme_channels);
  }
  return out;
}

}  // namespace performer
