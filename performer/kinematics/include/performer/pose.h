// Joint poses: a joint's local transform as translation + unit quaternion, the form that can be
// interpolated (matrices cannot be blended without shearing; Euler angles interpolate badly and
// wrap at +-180 degrees).
#pragma once

#include <span>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "performer/skeleton.h"

namespace performer {

struct JointPose {
  glm::vec3 translation{0.0f};                 // offset + position channels, in the parent's frame
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit quaternion, same convention as local_transforms
};

// Decodes one motion row into poses: the quaternion form of exactly what local_transforms builds.
// Throws std::invalid_argument on size mismatches.
void decode_pose(const Skeleton& skeleton, std::span<const float> frame_values, std::span<JointPose> out);

// out[j] = translate(pose.translation) * mat4_cast(pose.rotation). Sizes must match.
void poses_to_local(std::span<const JointPose> poses, std::span<glm::mat4> out);

// Spherical linear interpolation along the shorter of the two arcs between a and b (q and -q are
// the same rotation, so the sign is chosen to make the arc at most 180 degrees). t in [0, 1].
glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t);

// Translation interpolated linearly, rotation with slerp_shortest.
JointPose interpolate(const JointPose& a, const JointPose& b, float t);

}  // namespace performer
