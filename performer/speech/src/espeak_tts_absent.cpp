// EspeakTts in a build without espeak-ng (GPUJ2K_PERFORMER_SPEECH off): declared as usual so that
// callers compile unchanged, refusing with one line that says why when asked to speak.
#include <stdexcept>

#include "performer/espeak_tts.h"

namespace performer {

namespace {

[[noreturn]] void refuse() {
  throw std::runtime_error(
      "speech was not built: this performer was configured with -DGPUJ2K_PERFORMER_SPEECH=OFF, so it cannot speak "
      "text (use --keyframes, --rhubarb or --weights, or rebuild with libespeak-ng-dev installed)");
}

}  // namespace

bool EspeakTts::built() { return false; }

EspeakTts::EspeakTts() { refuse(); }

Speech EspeakTts::speak(std::string_view, std::string_view) { refuse(); }

std::vector<std::string> EspeakTts::languages() const { refuse(); }

}  // namespace performer
