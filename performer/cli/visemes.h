// `performer visemes`: text (through espeak-ng), a keyframe file or Rhubarb Lip Sync output in,
// blending weights per frame out (thesis 3.4.3-3.4.5), optionally with the synthesised speech as
// WAV. The weight track is also what `performer pose --text` drives the face with.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "performer/viseme_library.h"
#include "performer/speech.h"
#include "performer/weights_track.h"

namespace performer::cli {

struct LipSyncSource {
  std::string text;                   // spoken by espeak-ng in `language`
  std::string language;               // yue, cmn-latn-pinyin, ja, en-us
  std::filesystem::path keyframes;    // or: a manual keyframe file (phoneme_keyframes.h)
  std::filesystem::path rhubarb;      // or: Rhubarb Lip Sync TSV or JSON
  std::filesystem::path wav;          // with text: where to write the speech (empty: not written)
  std::string expression;             // a constant expression ("smile") ...
  double expression_weight = 0.5;     // ... at this weight
  std::filesystem::path expressions;  // or expression keyframes (weights_expression.h)
  std::string curve = "linear";       // linear (figure 3.8) or exponential (equation 3.8)
  bool blink = true;
  unsigned seed = 1;  // blink generator
  double fps = 30.0;
};

// Exactly one of text, keyframes and rhubarb must be given (std::invalid_argument otherwise).
// Writes the WAV when asked. Errors from the sources propagate with their file and line.
WeightTrack lip_sync_track(const LipSyncSource& source, const VisemeLibrary& library, Speech* speech = nullptr);

// Writes the track to `out` as CSV, or JSON when its extension is .json; atomically.
void write_track(const WeightTrack& track, const std::filesystem::path& out);

}  // namespace performer::cli
