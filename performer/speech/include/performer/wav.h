// The speech's audio as a WAV file (RIFF, 16-bit mono PCM), the format every audio tool and game
// engine reads, so the performer's voice can be played next to its animation.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace performer {

struct WavAudio {
  int sample_rate = 0;
  std::vector<std::int16_t> samples;  // mono
};

// Writes 16-bit mono PCM. Atomic: the bytes go to a temporary file in the same folder that is then
// renamed over `file`, so `file` is either the complete new WAV or untouched. Throws
// std::invalid_argument for a sample rate <= 0 or more samples than a WAV can hold, and
// std::runtime_error ("FILE: problem") when writing fails.
void write_wav(const std::filesystem::path& file, int sample_rate, std::span<const std::int16_t> samples);

// Reads a 16-bit mono PCM WAV (chunks other than "fmt " and "data" are skipped). Throws
// std::runtime_error ("FILE: problem") for a file that cannot be read, is not RIFF/WAVE, is
// another sample format, or whose sizes disagree with its length.
WavAudio read_wav(const std::filesystem::path& file);

}  // namespace performer
