// Manual timing (thesis 3.4.3, "Manual Weight Function Generation"): phoneme or syllable start
// times and durations marked by hand in a waveform editor, written one per line:
//
//   start  duration  symbol  language  [role]
//
// seconds as decimals; fields separated by tabs or spaces; '#' starts a comment; blank lines are
// ignored. role is onset, nucleus, coda or nasal to pick one table entry, or "syllable" to force
// splitting the symbol as a syllable. Without it, a symbol the table maps unambiguously is one
// phoneme, and anything else is split as a syllable ("zung1" -> z, u, ng).
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "performer/phoneme_role.h"
#include "performer/viseme_library.h"
#include "performer/viseme_timing.h"

namespace performer {

struct PhonemeKeyframe {
  double start = 0.0;
  double duration = 0.0;
  std::string symbol;
  std::string language;
  std::optional<PhonemeRole> role;  // given in the file (never PhonemeRole::any)
  bool syllable = false;            // "syllable" given in the file
  int line = 0;
};

// Throws VisemeDataError ("FILE:LINE: problem") for a wrong field count, a number that does not
// read, a negative duration or an unknown role word.
std::vector<PhonemeKeyframe> parse_phoneme_keyframes(std::string_view text, std::string_view file_name = "<keyframes>");
std::vector<PhonemeKeyframe> read_phoneme_keyframes(const std::filesystem::path& file);

// Visemes for the keyframes, sorted by start (stable). A symbol or language the library does not
// know is reported as VisemeDataError at the keyframe's line, naming the symbol.
std::vector<TimedViseme> keyframes_to_visemes(std::span<const PhonemeKeyframe> keyframes, const VisemeLibrary& library,
                                              std::string_view file_name = "<keyframes>");

}  // namespace performer
