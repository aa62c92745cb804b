// The blending-weight function of one viseme (thesis 3.4.3): where it is non-zero, and its shape
// there. Coarticulation lives in the windows: a viseme starts rising while its predecessor is still
// being spoken, so the two overlap (Figure 3.7).
//
// Linear (the thesis' choice, Figure 3.8): weight 1 at the viseme's start, falling linearly to 0 at
// its end; it rises from 0 to 1 over the preceding viseme, so between two starts one viseme falls
// exactly as the next rises and the two sum to 1. A viseme that follows silence (a gap, or nothing)
// rises over `lead_in` seconds before its start instead.
//
// Exponential (equation 3.8): alpha(t) = lambda * exp(-|t - (t_start + t_dur / 2)| / time_scale),
// peaking mid-viseme. time_scale = 1 s is the equation as printed (its exponent is in seconds);
// smaller values give a sharper peak. It is non-zero from the previous viseme's centre to the next
// one's (from lead_in before its start, and to its end, where there is no touching neighbour), so
// again only neighbours overlap.
#pragma once

#include <cstddef>
#include <span>

#include "performer/viseme_timing.h"

namespace performer {

enum class WeightCurve { linear, exponential };

struct WeightParams {
  WeightCurve curve = WeightCurve::linear;
  // Rise time (s) of a viseme with no touching predecessor. Shortened so it never reaches back
  // into the previous viseme. 0 makes such a viseme appear at full weight.
  double lead_in = 0.1;
  double lambda = 1.0;      // equation 3.8's peak weight, (0, 1]
  double time_scale = 1.0;  // equation 3.8's exponent divisor, seconds
  // Non-zero visemes kept per frame, strongest first: the thesis' vertex shader has two phoneme
  // DV streams (3.4.5).
  int max_visemes = 2;
  // Neighbours closer than this (s) count as touching: hand-typed times do not add up exactly.
  double contiguity = 1e-6;
};

// The interval where a viseme's weight is non-zero, and its peak.
struct DominanceWindow {
  double rise_start = 0.0;
  double peak = 0.0;
  double fall_end = 0.0;
};

// Equation 3.8 at time t, without any window.
double exponential_weight(double t, double start, double duration, double lambda, double time_scale);

// The Figure 3.8 ramp: 0 at or before rise_start, 1 at peak, 0 at or after fall_end, linear in
// between. A zero-length side is a step.
double ramp_weight(const DominanceWindow& window, double t);

// Windows for every viseme of a sequence sorted by start; out.size() == sequence.size().
void dominance_windows(std::span<const TimedViseme> sequence, const WeightParams& params,
                       std::span<DominanceWindow> out);

// One viseme's weight at t under `params.curve`, given its window from dominance_windows.
double viseme_curve_weight(const TimedViseme& viseme, const DominanceWindow& window, const WeightParams& params,
                           double t);

}  // namespace performer
