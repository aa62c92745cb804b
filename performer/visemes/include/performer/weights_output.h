// Writers for a WeightTrack. Numbers are written with std::to_chars, so the output does not depend
// on the C locale.
//
// CSV: a header "time,<channel>,...", then one row per frame.
// JSON: {"fps": F, "channels": [names], "time": [t...], "weights": {"<channel>": [w...], ...}}:
//       one curve per channel, the layout animation exporters (glTF samplers) want.
#pragma once

#include <ostream>

#include "performer/weights_track.h"

namespace performer {

void write_weights_csv(std::ostream& out, const WeightTrack& track);
void write_weights_json(std::ostream& out, const WeightTrack& track);

}  // namespace performer
