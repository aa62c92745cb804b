#include "performer/speech_visemes.h"

#include "performer/syllable_split.h"
#include "performer/viseme_error.h"

namespace performer {

std::vector<TimedViseme> speech_visemes(std::span<const TimedPhoneme> phonemes, const EspeakVisemeMap& map) {
  std::vector<TimedViseme> out;
  out.reserve(phonemes.size());
  std::vector<TimeSpan> pieces;
  for (const TimedPhoneme& p : phonemes) {
    const EspeakVisemeEntry* entry = find_espeak_visemes(map, p.name);
    if (!entry) throw UnmappedSymbolError(map.voice, p.name, PhonemeRole::any, "espeak-ng phoneme not in " + map.file);
    pieces.resize(entry->visemes.size());
    split_evenly({p.start, p.duration}, pieces);
    for (std::size_t i = 0; i < pieces.size(); ++i)
      out.push_back({pieces[i].start, pieces[i].duration, entry->visemes[i]});
  }
  return out;
}

}  // namespace performer
