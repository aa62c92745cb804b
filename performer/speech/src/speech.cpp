#include "performer/speech.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace performer {

double Speech::duration() const {
  if (sample_rate <= 0) return 0.0;
  return static_cast<double>(samples.size()) / sample_rate;
}

TextToSpeech::~TextToSpeech() = default;

std::vector<TimedPhoneme> phonemes_from_marks(std::span<const PhonemeMark> marks, double audio_end) {
  if (!std::isfinite(audio_end) || audio_end < 0.0)
    throw std::invalid_argument("phoneme timeline: audio end " + std::to_string(audio_end) + " is not a time");
  std::vector<PhonemeMark> sorted(marks.begin(), marks.end());
  for (const PhonemeMark& m : sorted)
    if (!std::isfinite(m.start))
      throw std::invalid_argument("phoneme timeline: phoneme '" + m.name + "' has no finite start");
  // Engines report in order, but a mark past the audio's end (rounding) or a reordering must not
  // give a negative duration: sort, then clamp into the audio.
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const PhonemeMark& a, const PhonemeMark& b) { return a.start < b.start; });
  std::vector<TimedPhoneme> out;
  out.reserve(sorted.size());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const double start = std::clamp(sorted[i].start, 0.0, audio_end);
    const double end = i + 1 < sorted.size() ? std::clamp(sorted[i + 1].start, 0.0, audio_end) : audio_end;
    out.push_back({std::move(sorted[i].name), start, end - start});
  }
  return out;
}

}  // namespace performer
