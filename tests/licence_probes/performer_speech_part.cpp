// A program linked against the performer's speech part alone, with every library on its link line
// kept as a dynamic dependency, for licence_boundary_test: it must show espeak-ng exactly when
// speech is built (GPUJ2K_PERFORMER_SPEECH), which also proves the inspection sees a GPL library
// where there is one. Built, not run by the tests: it says whether it can speak.
#include <cstdio>

#include "performer/espeak_tts.h"

int main() {
  std::printf("speech %s\n", performer::EspeakTts::built() ? "built" : "not built");
  return 0;
}
