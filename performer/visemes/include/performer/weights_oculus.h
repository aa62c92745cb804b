// Viseme weights renamed for face models rigged with the 15 Oculus visemes (sil, PP, ... ou): each
// thesis viseme's weight goes to its Oculus viseme (visemes.tsv), summed where several share one and
// clamped to 1. The thesis set is kept as the computing set because its tables are defined on it.
#pragma once

#include <span>

#include "performer/viseme_set.h"
#include "performer/weights_track.h"

namespace performer {

// out[k] = min(1, sum of weights of the visemes whose Oculus name is kOculusVisemes[k]);
// out.size() == 15, weights.size() == set.size().
void fold_to_oculus(std::span<const float> weights, const VisemeSet& set, std::span<float> out);

// The track with its viseme channels replaced by the 15 Oculus channels; other channels unchanged.
WeightTrack oculus_track(const WeightTrack& track, const VisemeSet& set);

}  // namespace performer
