// Timing from Rhubarb Lip Sync (speech-driven: it analyses a recording and emits mouth shapes A-H
// and X). Two of its output formats are read:
//
//   TSV:  one cue per line, "time<TAB>shape"; a cue lasts until the next one starts, and the last
//         (Rhubarb writes X at the end of the sound) has no length.
//   JSON: {"metadata": {...}, "mouthCues": [{"start": 0.00, "end": 0.05, "value": "X"}, ...]};
//         other members are skipped.
//
// Shapes map to visemes through data/visemes/rhubarb.tsv (language "rhubarb"), which documents
// each choice.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "performer/viseme_library.h"
#include "performer/viseme_timing.h"

namespace performer {

inline constexpr std::string_view kRhubarbLanguage = "rhubarb";

struct MouthCue {
  double start = 0.0;
  double end = 0.0;
  std::string shape;  // "A" ... "H" or "X"
  int line = 0;
};

// "A" to "H" or "X": Rhubarb's six basic and three extended shapes.
bool is_rhubarb_shape(std::string_view shape);

// Both throw VisemeDataError ("FILE:LINE: problem") for unreadable numbers, shapes other than A-H
// and X, cues that go back in time, or (JSON) a document of another shape.
std::vector<MouthCue> parse_rhubarb_tsv(std::string_view text, std::string_view file_name = "<rhubarb>");
std::vector<MouthCue> parse_rhubarb_json(std::string_view text, std::string_view file_name = "<rhubarb>");

// Reads either format, told apart by the first non-blank character ('{' is JSON).
std::vector<MouthCue> read_rhubarb(const std::filesystem::path& file);

std::vector<TimedViseme> rhubarb_to_visemes(std::span<const MouthCue> cues, const VisemeLibrary& library);

}  // namespace performer
