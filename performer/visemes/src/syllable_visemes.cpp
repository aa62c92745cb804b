#include "performer/syllable_visemes.h"

#include <algorithm>

#include "performer/syllable_parse.h"
#include "performer/viseme_error.h"

namespace performer {

namespace {

// Appends the phonemes of one role, sharing `span` evenly among them.
void append_role(const VisemeTable& table, const std::vector<SyllablePhoneme>& phonemes, PhonemeRole role,
                 TimeSpan span, std::vector<TimedViseme>& out) {
  std::vector<const SyllablePhoneme*> of_role;
  for (const SyllablePhoneme& p : phonemes)
    if (p.role == role) of_role.push_back(&p);
  std::vector<TimeSpan> pieces(of_role.size());
  split_evenly(span, pieces);
  for (std::size_t i = 0; i < of_role.size(); ++i)
    out.push_back({pieces[i].start, pieces[i].duration, viseme_for(table, of_role[i]->symbol, role)});
}

}  // namespace

std::vector<TimedViseme> syllable_visemes(const VisemeTable& table, std::string_view syllable, double start,
                                          double duration, double onset_fraction) {
  const auto phonemes = parse_syllable(table, syllable);
  if (!phonemes)
    throw UnmappedSymbolError(table.language, std::string(syllable), PhonemeRole::any,
                              "cannot be split into onset, nucleus and coda with the symbols of " + table.file);
  std::vector<TimedViseme> out;
  if (phonemes->size() == 1 && phonemes->front().role == PhonemeRole::nasal) {
    split_syllable(start, duration, false, false, onset_fraction);  // validates the timing
    out.push_back({start, duration, viseme_for(table, phonemes->front().symbol, PhonemeRole::nasal)});
    return out;
  }
  const auto has = [&](PhonemeRole r) {
    return std::any_of(phonemes->begin(), phonemes->end(), [r](const SyllablePhoneme& p) { return p.role == r; });
  };
  const SyllableSpans spans =
      split_syllable(start, duration, has(PhonemeRole::onset), has(PhonemeRole::coda), onset_fraction);
  if (spans.onset) append_role(table, *phonemes, PhonemeRole::onset, *spans.onset, out);
  append_role(table, *phonemes, PhonemeRole::nucleus, spans.nucleus, out);
  if (spans.coda) append_role(table, *phonemes, PhonemeRole::coda, *spans.coda, out);
  return out;
}

}  // namespace performer
