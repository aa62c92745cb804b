// A timed syllable to timed visemes: parse it into phonemes (syllable_parse.h), share its duration
// out (syllable_split.h), and look each phoneme up in the language's table. This is the thesis'
// automatic path from CU Vocal's syllable timings to viseme timings (3.4.3).
#pragma once

#include <string_view>
#include <vector>

#include "performer/syllable_split.h"
#include "performer/viseme_table.h"
#include "performer/viseme_timing.h"

namespace performer {

// Visemes in spoken order. Throws UnmappedSymbolError when the syllable cannot be split with the
// table's symbols; std::invalid_argument for bad timing (see split_syllable).
std::vector<TimedViseme> syllable_visemes(const VisemeTable& table, std::string_view syllable, double start,
                                          double duration, double onset_fraction = kOnsetFraction);

}  // namespace performer
