#include "dwt/params.h"

#include "dwt/error.h"

#include <string>

namespace dwt {

void validate(const DwtParams& p, int width, int height) {
  if (width <= 0 || height <= 0)
    throw DwtError("empty plane (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  if (p.origin.x < 0 || p.origin.y < 0) throw DwtError("the origin on the reference grid must be non-negative");
  if (p.levels < 0) throw DwtError("negative level count");
  if (p.levels > 32) throw DwtError(std::to_string(p.levels) + " levels requested; JPEG 2000 allows at most 32");
  if (p.levels_may_exceed_size) return;
  const int most = max_levels(width, height, p.origin);
  if (p.levels > most)
    throw DwtError(std::to_string(p.levels) + " levels requested but a " + std::to_string(width) + "x" +
                   std::to_string(height) + " plane allows at most " + std::to_string(most));
}

}  // namespace dwt
