#include "performer/weights_track.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "performer/weights_visemes.h"

namespace performer {

int WeightTrack::channel(std::string_view name) const {
  for (std::size_t i = 0; i < channels.size(); ++i)
    if (channels[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<double> frame_times(double begin, double end, double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw std::invalid_argument("fps must be > 0");
  if (!std::isfinite(begin) || !std::isfinite(end) || end < begin)
    throw std::invalid_argument("frame_times: need finite begin <= end");
  // The tolerance keeps an end that is a whole number of frames (1.0 s at 30 fps) from losing its
  // last frame to rounding.
  const auto count = static_cast<std::size_t>(std::floor((end - begin) * fps + 1e-6)) + 1;
  std::vector<double> times(count);
  for (std::size_t k = 0; k < count; ++k) times[k] = begin + static_cast<double>(k) / fps;
  return times;
}

namespace {

double natural_end(std::span<const TimedViseme> visemes, std::span<const ExpressionKey> expressions, double begin) {
  double end = begin;
  for (const TimedViseme& v : visemes) end = std::max(end, v.end());
  for (const ExpressionKey& k : expressions) end = std::max(end, k.time);
  return end;
}

}  // namespace

WeightTrack build_weight_track(std::span<const TimedViseme> visemes, const VisemeSet& set,
                               std::span<const ExpressionKey> expressions, const TrackOptions& options) {
  check_weight_params(options.weights);
  check_viseme_sequence(visemes, set.size());
  if (options.max_expressions < 1) throw std::invalid_argument("max_expressions must be >= 1");
  const double end = options.end < 0.0 ? natural_end(visemes, expressions, options.begin) : options.end;

  WeightTrack track;
  track.fps = options.fps;
  track.times = frame_times(options.begin, end, options.fps);
  for (const VisemeInfo& v : set.visemes) track.channels.push_back(v.name);
  track.viseme_channels = set.size();
  const std::vector<std::string> names = expression_names(expressions);
  for (const std::string& n : names) {
    // A column name must say which face model it drives.
    if (set.find(n) >= 0 || n == "blink")
      throw std::invalid_argument("expression '" + n + "' has the name of another channel");
    track.channels.push_back(n);
  }
  std::vector<Blink> blinks;
  if (options.blink) {
    blinks = generate_blinks(options.blink_params, options.begin, end);
    track.channels.push_back("blink");
  }

  const std::size_t width = track.channels.size();
  const auto viseme_width = static_cast<std::size_t>(set.size());
  track.values.assign(track.times.size() * width, 0.0f);
  std::vector<DominanceWindow> windows(visemes.size());
  dominance_windows(visemes, options.weights, windows);
  for (std::size_t f = 0; f < track.times.size(); ++f) {
    const double t = track.times[f];
    const std::span<float> row = std::span<float>(track.values).subspan(f * width, width);
    viseme_weights_at(visemes, windows, options.weights, t, row.first(viseme_width));
    expression_weights_at(expressions, names, t, options.max_expressions, row.subspan(viseme_width, names.size()));
    if (options.blink) row.back() = static_cast<float>(blink_weight(blinks, options.blink_params.close_fraction, t));
  }
  return track;
}

}  // namespace performer
