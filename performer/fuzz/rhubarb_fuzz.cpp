// libFuzzer entry point for the Rhubarb Lip Sync readers (TSV and JSON): the first input byte
// picks the format. Rejected input must surface as VisemeDataError; any other exception, crash or
// sanitizer report is a bug, and so is an accepted cue list with a cue that ends before it starts,
// a non-finite time or a shape outside Rhubarb's A-H and X.
//
//   cmake -DCMAKE_CXX_COMPILER=clang++ -DGPUJ2K_FUZZ=ON ... && build/bin/rhubarb_fuzz

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "performer/viseme_error.h"
#include "performer/viseme_rhubarb.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const std::vector<performer::MouthCue> cues = (data[0] & 1) ? performer::parse_rhubarb_json(text, "fuzz-input")
                                                                : performer::parse_rhubarb_tsv(text, "fuzz-input");
    for (const performer::MouthCue& cue : cues) {
      if (!std::isfinite(cue.start) || !std::isfinite(cue.end) || cue.end < cue.start) std::abort();
      if (cue.shape.size() != 1 || !((cue.shape[0] >= 'A' && cue.shape[0] <= 'H') || cue.shape[0] == 'X')) std::abort();
    }
  } catch (const performer::VisemeDataError&) {
    // Expected for malformed input.
  }
  return 0;
}
