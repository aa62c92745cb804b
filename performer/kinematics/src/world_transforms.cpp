#include "performer/world_transforms.h"

#include <stdexcept>
#include <string>

namespace performer {

void world_transforms(const Skeleton& skeleton, std::span<const glm::mat4> local, std::span<glm::mat4> out) {
  const std::size_t n = skeleton.joints.size();
  if (local.size() != n || out.size() != n)
    throw std::invalid_argument("world_transforms: " + std::to_string(local.size()) + " locals and " +
                                std::to_string(out.size()) + " outputs for " + std::to_string(n) + " joints");
  for (std::size_t j = 0; j < n; ++j) {
    const int parent = skeleton.joints[j].parent;
    if (parent < 0) {
      out[j] = local[j];
    } else if (static_cast<std::size_t>(parent) < j) {
      out[j] = out[static_cast<std::size_t>(parent)] * local[j];
    } else {
      // A hand-built skeleton out of order would otherwise read a world transform not yet written.
      throw std::invalid_argument("world_transforms: joint " + std::to_string(j) + " has parent " +
                                  std::to_string(parent) + ", which does not precede it");
    }
  }
}

}  // namespace performer
