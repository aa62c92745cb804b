// All blending weights of a performance, sampled at a frame rate: the viseme channels alpha_i(t),
// the expression channels beta_j(t) and the blink channel of equation 3.9 plus the eye stream
// (3.4.5). One row per frame, one column per channel: what a renderer or exporter consumes.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "performer/blink_generator.h"
#include "performer/viseme_set.h"
#include "performer/viseme_timing.h"
#include "performer/weights_curves.h"
#include "performer/weights_expression.h"

namespace performer {

struct WeightTrack {
  double fps = 30.0;
  std::vector<double> times;          // seconds, one per frame
  std::vector<std::string> channels;  // viseme names, then expression names, then "blink"
  int viseme_channels = 0;            // how many leading channels are visemes
  std::vector<float> values;          // frame-major: times.size() * channels.size()

  std::size_t frame_count() const { return times.size(); }
  std::size_t channel_count() const { return channels.size(); }
  std::span<const float> frame(std::size_t f) const {
    return std::span<const float>(values).subspan(f * channels.size(), channels.size());
  }
  // The column with this name; -1 when there is none.
  int channel(std::string_view name) const;
};

struct TrackOptions {
  double fps = 30.0;
  double begin = 0.0;
  // Last frame time; negative means up to the end of the last viseme or expression key.
  double end = -1.0;
  WeightParams weights;
  int max_expressions = 2;  // the shader's two expression DV streams
  bool blink = true;        // add the "blink" channel
  BlinkParams blink_params;
};

// Frame times begin, begin + 1/fps, ... up to and including end (within a millionth of a frame).
// Throws std::invalid_argument for fps <= 0 or end < begin.
std::vector<double> frame_times(double begin, double end, double fps);

// Throws std::invalid_argument for bad options or inputs (see check_viseme_sequence,
// check_weight_params, generate_blinks) and for an expression named like a viseme or "blink".
WeightTrack build_weight_track(std::span<const TimedViseme> visemes, const VisemeSet& set,
                               std::span<const ExpressionKey> expressions, const TrackOptions& options);

}  // namespace performer
