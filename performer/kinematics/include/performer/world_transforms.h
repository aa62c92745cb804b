// Forward kinematics, step 2: accumulate local transforms down the hierarchy, "stacking series of
// transformation matrices as we enter each body part" (thesis 3.5.1).
#pragma once

#include <span>

#include <glm/mat4x4.hpp>

#include "performer/skeleton.h"

namespace performer {

// out[j] = out[parent_j] * local[j], or local[j] for a root. One forward pass: the skeleton keeps
// parents before children. To place the whole figure in a scene, premultiply the roots' locals.
// Throws std::invalid_argument on size mismatches or a parent that does not precede its child.
// `out` may not alias `local`.
void world_transforms(const Skeleton& skeleton, std::span<const glm::mat4> local, std::span<glm::mat4> out);

}  // namespace performer
