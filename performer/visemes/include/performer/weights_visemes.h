// Per-frame viseme weights alpha_i(t) (thesis equation 3.7) from a timed viseme sequence: every
// viseme's curve (weights_curves.h) summed per viseme ID, clamped to [0, 1], then all but the
// strongest `max_visemes` set to 0, because the vertex shader blends two phoneme DVs (3.4.5).
#pragma once

#include <cstddef>
#include <span>

#include "performer/viseme_timing.h"
#include "performer/weights_curves.h"

namespace performer {

// Throws std::invalid_argument unless starts are finite and non-decreasing, durations finite and
// >= 0, and IDs in [0, viseme_count).
void check_viseme_sequence(std::span<const TimedViseme> sequence, int viseme_count);

// Throws std::invalid_argument for lead_in < 0, lambda outside (0, 1], time_scale <= 0, max_visemes
// < 1 or contiguity < 0 (or any of them not finite).
void check_weight_params(const WeightParams& params);

// Keeps the `keep` largest entries and zeroes the rest; equal weights go to the lower index. Zeros
// stay zeros, so fewer than `keep` entries may remain non-zero.
void keep_strongest(std::span<float> weights, int keep);

// One frame: out[id] for every viseme ID (out.size() is the viseme count). `windows` from
// dominance_windows for the same sequence and params. Sums repeats of an ID (a viseme said twice in
// a row holds its shape instead of dipping between them) and clamps to [0, 1].
void viseme_weights_at(std::span<const TimedViseme> sequence, std::span<const DominanceWindow> windows,
                       const WeightParams& params, double t, std::span<float> out);

// All frames: out is frame-major, times.size() * viseme_count values. Checks its inputs.
void viseme_weight_frames(std::span<const TimedViseme> sequence, const WeightParams& params,
                          std::span<const double> times, int viseme_count, std::span<float> out);

}  // namespace performer
