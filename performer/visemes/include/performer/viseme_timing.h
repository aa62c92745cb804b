// A viseme held over a time interval: what every timing source (TTS syllables, manual keyframes,
// Rhubarb cues) is reduced to before blending weights are computed from it.
#pragma once

namespace performer {

struct TimedViseme {
  double start = 0.0;     // seconds
  double duration = 0.0;  // seconds, >= 0
  int viseme = 0;         // ID in the viseme set
  double end() const { return start + duration; }
};

}  // namespace performer
