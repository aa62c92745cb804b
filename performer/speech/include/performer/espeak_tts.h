// TextToSpeech on espeak-ng (https://github.com/espeak-ng/espeak-ng), the free multilingual
// synthesiser that stands in for the thesis' CU Vocal: it reports every phoneme it speaks with its
// position in the audio, which is what the lip sync needs.
//
// espeak-ng is GPL-3.0-or-later; it is linked into the performer's speech part only
// (speech/CMakeLists.txt), and only when GPUJ2K_PERFORMER_SPEECH is on. Without it this class is
// still declared, so callers compile unchanged, but built() is false and constructing one throws.
//
// Languages (each is the espeak-ng voice of that name):
//   yue              Cantonese; text in hanzi ("你好").
//   cmn-latn-pinyin  Mandarin; text in Hanyu Pinyin with tone digits ("ni3 hao3", ü as v or ü).
//                    Hanzi are refused: this voice would not read them as Mandarin, and converting
//                    hanzi to pinyin needs a dictionary this project does not have.
//   ja               Japanese; text in kana. Kanji are refused: espeak-ng has no kanji readings and
//                    would spell each one out in English ("Chinese letter").
//   en-us            American English.
// Latin words inside yue, cmn-latn-pinyin or ja text make espeak-ng switch to English phonemes for
// them; the speech comes back, but those phonemes are not in the voice's viseme mapping
// (espeak_visemes.h), which then reports them.
//
// espeak-ng is one process-wide instance (see speech/src/espeak_engine.h): EspeakTts objects share
// it and their calls are serialised, so any number of them may be used from any threads.
// espeak-ng carries some synthesis state from one call to the next, so the same text twice is not
// bit-identical: lengths and phoneme times may differ by a few samples (about a millisecond).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "performer/speech.h"

namespace performer {

class EspeakTts final : public TextToSpeech {
 public:
  // Whether this build has the engine (configured with GPUJ2K_PERFORMER_SPEECH on).
  static bool built();

  // Initialises espeak-ng for the process if no one has yet. Throws std::runtime_error when its
  // data (Debian: espeak-ng-data) cannot be loaded, or when speech was not built (see built()).
  EspeakTts();

  // 22050 Hz mono audio; phonemes named with espeak-ng's mnemonics ("n", "ei", "_|": pauses start
  // with '_'). Tones and stress are properties of the vowels and come as no phoneme of their own.
  // Throws std::invalid_argument for an unknown language, empty or non-UTF-8 text, ideographs
  // where the language refuses them, or text with nothing to say (only punctuation);
  // std::runtime_error when espeak-ng fails.
  Speech speak(std::string_view text, std::string_view language) override;

  std::vector<std::string> languages() const override;
};

}  // namespace performer
