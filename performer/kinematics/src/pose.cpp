#include "performer/pose.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "joint_channels.h"

namespace performer {

void decode_pose(const Skeleton& skeleton, std::span<const float> frame_values, std::span<JointPose> out) {
  if (out.size() != skeleton.joints.size())
    throw std::invalid_argument("decode_pose: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(skeleton.joints.size()) + " joints");
  if (frame_values.size() != static_cast<std::size_t>(channel_count(skeleton)))
    throw std::invalid_argument("decode_pose: frame has " + std::to_string(frame_values.size()) +
                                " values, the skeleton " + std::to_string(channel_count(skeleton)) + " channels");
  for (std::size_t j = 0; j < out.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    out[j].translation = detail::joint_translation(joint, frame_values);
    out[j].rotation = detail::joint_rotation_quat(joint, frame_values);
  }
}

void poses_to_local(std::span<const JointPose> poses, std::span<glm::mat4> out) {
  if (out.size() != poses.size())
    throw std::invalid_argument("poses_to_local: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(poses.size()) + " poses");
  for (std::size_t j = 0; j < poses.size(); ++j) {
    out[j] = glm::mat4_cast(poses[j].rotation);
    out[j][3] = glm::vec4(poses[j].translation, 1.0f);
  }
}

glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t) {
  float cos_angle = glm::dot(a, b);
  glm::quat end = b;
  if (cos_angle < 0.0f) {
    end = -b;
    cos_angle = -cos_angle;
  }
  // Nearly equal rotations: sin(angle) -> 0 makes the slerp weights 0/0, while the normalised
  // linear blend is indistinguishable from slerp at that angle.
  if (cos_angle > 0.9995f) {
    const glm::quat q = a * (1.0f - t) + end * t;
    return glm::normalize(q);
  }
  const float angle = std::acos(cos_angle);
  const float inv_sin = 1.0f / std::sin(angle);
  const float wa = std::sin((1.0f - t) * angle) * inv_sin;
  const float wb = std::sin(t * angle) * inv_sin;
  return a * wa + end * wb;
}

JointPose interpolate(const JointPose& a, const JointPose& b, float t) {
  return JointPose{a.translation + (b.translation - a.translation) * t, slerp_shortest(a.rotation, b.rotation, t)};
}

}  // namespace performer
