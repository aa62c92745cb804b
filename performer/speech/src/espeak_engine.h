// The process's one espeak-ng session. espeak-ng keeps all of its state in globals (one voice, one
// output mode, one callback, one set of buffers), so this file is the only caller of its API: a
// single mutex serialises every call, and the library is initialised once, on first use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "performer/speech.h"

namespace performer::detail {

struct EspeakAudio {
  int sample_rate = 0;
  std::vector<std::int16_t> samples;
  // One mark per phoneme event, in the order espeak-ng reported them. Its "(en)"-style events,
  // which announce a switch to another language's phoneme table and are not sounds, are dropped.
  std::vector<PhonemeMark> marks;
};

// Initialises espeak-ng unless done already: data from its compiled-in folder or $ESPEAK_DATA_PATH,
// synchronous output (the audio comes to us; no sound device is opened, so ALSA stays silent) and
// phoneme events on. Throws std::runtime_error when espeak-ng cannot load its data.
//
// Side effect of espeak-ng itself, process-wide: its initialisation sets the C locale's LC_CTYPE
// to a UTF-8 one (its text reading depends on it).
void espeak_start();

// Speaks UTF-8 text with an espeak-ng voice (espeak_start() first, if needed). Throws
// std::invalid_argument for a voice espeak-ng does not have, std::runtime_error when synthesis
// fails.
EspeakAudio espeak_synthesize(const std::string& voice, const std::string& text);

}  // namespace performer::detail
