#include "performer/skeleton.h"

#include <stdexcept>

namespace performer {

std::string_view channel_name(Channel channel) {
  switch (channel) {
    case Channel::Xposition:
      return "Xposition";
    case Channel::Yposition:
      return "Yposition";
    case Channel::Zposition:
      return "Zposition";
    case Channel::Xrotation:
      return "Xrotation";
    case Channel::Yrotation:
      return "Yrotation";
    case Channel::Zrotation:
      return "Zrotation";
  }
  return "?";
}

int channel_count(const Skeleton& skeleton) {
  int count = 0;
  for (const Joint& joint : skeleton.joints) count += static_cast<int>(joint.channels.size());
  return count;
}

int animated_joint_count(const Skeleton& skeleton) {
  int count = 0;
  for (const Joint& joint : skeleton.joints) count += joint.end_site ? 0 : 1;
  return count;
}

int find_joint(const Skeleton& skeleton, std::string_view name) {
  for (std::size_t i = 0; i < skeleton.joints.size(); ++i)
    if (skeleton.joints[i].name == name) return static_cast<int>(i);
  return -1;
}

std::span<const float> frame_values(const Skeleton& skeleton, const Motion& motion, int frame) {
  const auto channels = static_cast<std::size_t>(channel_count(skeleton));
  if (motion.frames < 0 || motion.values.size() != channels * static_cast<std::size_t>(motion.frames))
    throw std::invalid_argument("motion holds " + std::to_string(motion.values.size()) + " values, expected " +
                                std::to_string(motion.frames) + " frames of " + std::to_string(channels));
  if (frame < 0 || frame >= motion.frames)
    throw std::out_of_range("frame " + std::to_string(frame) + " outside the motion's " +
                            std::to_string(motion.frames) + " frames");
  return std::span<const float>(motion.values).subspan(static_cast<std::size_t>(frame) * channels, channels);
}

double last_frame_time(const Motion& motion) {
  return motion.frames > 1 ? (motion.frames - 1) * motion.frame_time : 0.0;
}

}  // namespace performer
