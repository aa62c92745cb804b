// Forward kinematics, step 1 (thesis section 3.5.3): each joint's transform relative to its parent
// for one motion row. The equation X = f(theta) of (3.12) is this job followed by world_transforms.
#pragma once

#include <span>

#include <glm/mat4x4.hpp>

#include "performer/skeleton.h"

namespace performer {

// out[j] = translate(offset_j + position channels_j) * R_j, where R_j multiplies the joint's axis
// rotations in the order its channels are listed (ZYX -> Rz * Ry * Rx), angles in degrees.
// frame_values: one motion row (channel_count(skeleton) values); out: one matrix per joint.
// Throws std::invalid_argument on size mismatches.
void local_transforms(const Skeleton& skeleton, std::span<const float> frame_values, std::span<glm::mat4> out);

// The rest (bind) pose: out[j] = translate(offset_j), as if every channel were zero.
void rest_local_transforms(const Skeleton& skeleton, std::span<glm::mat4> out);

}  // namespace performer
