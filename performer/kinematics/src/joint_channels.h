// Turning one joint's slice of a motion row into a translation and a rotation. Private: shared by
// local_transforms (matrices) and decode_pose (quaternions) so the two can never disagree on the
// BVH conventions spelled out here.
//
// Conventions (those of every BVH writer we know, and of the thesis' motion capture pipeline):
//  * translation = OFFSET + the position channels, whatever their place in the channel list;
//  * rotations are in degrees and compose in listed order: "Zrotation Yrotation Xrotation" means
//    R = Rz * Ry * Rx, i.e. applied to a vector X first. Each axis rotation is right-handed.
#pragma once

#include <cmath>
#include <numbers>
#include <span>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "performer/skeleton.h"

namespace performer::detail {

// Sine and cosine in double: the angle is converted once, and float trig of large degree values
// (mocap roots can spin past 360) loses digits we would rather keep.
struct SinCos {
  float s, c;
};
inline SinCos sin_cos_degrees(float degrees) {
  const double radians = static_cast<double>(degrees) * (std::numbers::pi / 180.0);
  return {static_cast<float>(std::sin(radians)), static_cast<float>(std::cos(radians))};
}

inline glm::vec3 joint_translation(const Joint& joint, std::span<const float> row) {
  glm::vec3 t = joint.offset;
  for (std::size_t i = 0; i < joint.channels.size(); ++i) {
    const Channel c = joint.channels[i];
    if (!is_rotation(c)) t[channel_axis(c)] += row[static_cast<std::size_t>(joint.channel_offset) + i];
  }
  return t;
}

// Rotation about one coordinate axis; glm matrices are column-major, m[column][row].
inline glm::mat3 axis_rotation_matrix(int axis, float degrees) {
  const auto [s, c] = sin_cos_degrees(degrees);
  glm::mat3 m(1.0f);
  const int a = (axis + 1) % 3;  // the two axes spanning the plane of rotation, in cyclic order,
  const int b = (axis + 2) % 3;  // so one formula serves X (y,z), Y (z,x) and Z (x,y)
  m[a][a] = c;
  m[a][b] = s;
  m[b][a] = -s;
  m[b][b] = c;
  return m;
}

inline glm::quat axis_rotation_quat(int axis, float degrees) {
  const auto [s, c] = sin_cos_degrees(degrees * 0.5f);
  glm::quat q(c, 0.0f, 0.0f, 0.0f);  // glm's constructor order is (w, x, y, z)
  q[axis] = s;                       // ... but its subscript order is x, y, z, w
  return q;
}

inline glm::mat3 joint_rotation_matrix(const Joint& joint, std::span<const float> row) {
  glm::mat3 r(1.0f);
  for (std::size_t i = 0; i < joint.channels.size(); ++i) {
    const Channel c = joint.channels[i];
    if (is_rotation(c))
      r = r * axis_rotation_matrix(channel_axis(c), row[static_cast<std::size_t>(joint.channel_offset) + i]);
  }
  return r;
}

inline glm::quat joint_rotation_quat(const Joint& joint, std::span<const float> row) {
  glm::quat q(1.0f, 0.0f, 0.0f, 0.0f);
  for (std::size_t i = 0; i < joint.channels.size(); ++i) {
    const Channel c = joint.channels[i];
    if (is_rotation(c))
      q = q * axis_rotation_quat(channel_axis(c), row[static_cast<std::size_t>(joint.channel_offset) + i]);
  }
  return q;
}

}  // namespace performer::detail
