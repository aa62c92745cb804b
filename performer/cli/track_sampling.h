// Reading a weight track at video or mesh frame times, for `performer pose` and `performer render`.
#pragma once

#include <span>

#include "performer/weights_track.h"

namespace performer::cli {

// The track's channel values at `seconds`: linear between the two surrounding frames (weights are
// sampled curves, so linear interpolation is what a renderer between samples would do), clamped to
// the first and last frame. `out` has one value per channel.
void sample_track(const WeightTrack& track, double seconds, std::span<float> out);

// Keeps the `count` largest of `weights` (ties to the lower index) and sets the rest to 0: a frame
// between two track frames can have one viseme more acting than the shader's DV streams take.
void keep_strongest(std::span<float> weights, int count);

}  // namespace performer::cli
