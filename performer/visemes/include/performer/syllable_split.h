// When only a syllable's start and duration are known (CU Vocal reports syllables, not phonemes),
// how long each of its parts lasts (thesis 3.4.3, the /zung/ example).
//
// Our reading of the thesis: the onset (initial) takes 0.25 of the syllable; the final takes the
// rest, shared equally by nucleus and coda ("we assume the nucleus and coda have equal average
// durations": 0.25 / 0.375 / 0.375). A final without a coda is all nucleus (0.25 / 0.75). A syllable
// without an onset has no quarter to give away: its final fills the whole syllable, so the nucleus
// starts at the syllable start (0.5 / 0.5 with a coda, 1 without). Leaving the first quarter empty
// would close the mouth in the middle of speech.
#pragma once

#include <optional>
#include <span>

namespace performer {

inline constexpr double kOnsetFraction = 0.25;

struct TimeSpan {
  double start = 0.0;
  double duration = 0.0;
  double end() const { return start + duration; }
};

struct SyllableSpans {
  std::optional<TimeSpan> onset;
  TimeSpan nucleus;
  std::optional<TimeSpan> coda;
};

// Throws std::invalid_argument for a negative or non-finite duration, a non-finite start, or an
// onset_fraction outside [0, 1).
SyllableSpans split_syllable(double start, double duration, bool has_onset, bool has_coda,
                             double onset_fraction = kOnsetFraction);

// Cuts `span` into out.size() equal consecutive pieces: an onset cluster or a multi-letter nucleus
// (Mandarin "ao") shares its part of the syllable evenly. The last piece ends exactly at span.end().
void split_evenly(TimeSpan span, std::span<TimeSpan> out);

}  // namespace performer
