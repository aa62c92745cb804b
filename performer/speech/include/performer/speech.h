// Text to speech for the performer: the audio and the phonemes it is made of, timed in the audio's
// own time base. The thesis drives its lip sync from the timings its TTS (CU Vocal) reports
// (3.4.3); keeping sound and phonemes in one result is what keeps mouth and voice in step.
// Engines implement TextToSpeech (espeak_tts.h); speech_visemes.h turns the phonemes into visemes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace performer {

struct TimedPhoneme {
  std::string name;       // the engine's own phoneme mnemonic (espeak-ng: "n", "ei", "_|", ...)
  double start = 0.0;     // seconds from the first sample
  double duration = 0.0;  // seconds, >= 0
  double end() const { return start + duration; }
};

struct Speech {
  int sample_rate = 0;                 // Hz
  std::vector<std::int16_t> samples;   // mono PCM
  std::vector<TimedPhoneme> phonemes;  // ordered by start, non-overlapping
  // Seconds of audio; 0 without a sample rate.
  double duration() const;
};

class TextToSpeech {
 public:
  virtual ~TextToSpeech();
  // Throws std::invalid_argument for a language not in languages() (the message names those there
  // are) or text the language cannot take (empty, wrong script, nothing to say);
  // std::runtime_error when the engine itself fails.
  virtual Speech speak(std::string_view text, std::string_view language) = 0;
  virtual std::vector<std::string> languages() const = 0;
};

// A phoneme and when it starts, which is all engines report (an event per phoneme, no end).
struct PhonemeMark {
  std::string name;
  double start = 0.0;  // seconds
};

// Timed phonemes from start marks: sorted by start (stably, so equal starts keep their order), each
// start clamped to [0, audio_end], each phoneme lasting until the next starts and the last until
// audio_end. The result is ordered and non-overlapping by construction. Throws
// std::invalid_argument for a negative or non-finite audio_end or a non-finite start.
std::vector<TimedPhoneme> phonemes_from_marks(std::span<const PhonemeMark> marks, double audio_end);

}  // namespace performer
