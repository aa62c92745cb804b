#include "performer/syllable_split.h"

#include <cmath>
#include <stdexcept>

namespace performer {

SyllableSpans split_syllable(double start, double duration, bool has_onset, bool has_coda, double onset_fraction) {
  if (!std::isfinite(start) || !std::isfinite(duration) || duration < 0.0)
    throw std::invalid_argument("split_syllable: start must be finite and duration finite and non-negative");
  if (!(onset_fraction >= 0.0 && onset_fraction < 1.0))
    throw std::invalid_argument("split_syllable: onset_fraction must be in [0, 1)");
  const double end = start + duration;
  SyllableSpans spans;
  const double onset = has_onset ? onset_fraction * duration : 0.0;
  if (has_onset) spans.onset = TimeSpan{start, onset};
  const double final_start = start + onset;
  const double final_duration = end - final_start;
  if (has_coda) {
    const double half = 0.5 * final_duration;
    spans.nucleus = {final_start, half};
    // The coda ends exactly at the syllable end, so consecutive syllables touch without rounding gaps.
    spans.coda = TimeSpan{final_start + half, end - (final_start + half)};
  } else {
    spans.nucleus = {final_start, final_duration};
  }
  return spans;
}

void split_evenly(TimeSpan span, std::span<TimeSpan> out) {
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double begin = span.start + span.duration * static_cast<double>(i) / static_cast<double>(n);
    const double end =
        i + 1 == n ? span.end() : span.start + span.duration * static_cast<double>(i + 1) / static_cast<double>(n);
    out[i] = {begin, end - begin};
  }
}

}  // namespace performer
