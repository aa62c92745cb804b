// Lip sync from synthesised speech: the espeak-ng phonemes of a Speech, in its own time base, to the
// timed visemes every timing source is reduced to (viseme_timing.h). This is the thesis' path from
// TTS timings to visemes (3.4.3), with per-phoneme timings where CU Vocal gave per-syllable ones.
#pragma once

#include <span>
#include <vector>

#include "performer/espeak_visemes.h"
#include "performer/speech.h"
#include "performer/viseme_timing.h"

namespace performer {

// One viseme per mapping target, in order; a phoneme mapped to several visemes shares its time
// evenly among them (split_evenly). Pauses are whatever the mapping says (the shipped files map
// them to the closed face). Throws UnmappedSymbolError naming the map's voice and the mnemonic for
// a phoneme the mapping lacks.
std::vector<TimedViseme> speech_visemes(std::span<const TimedPhoneme> phonemes, const EspeakVisemeMap& map);

}  // namespace performer
