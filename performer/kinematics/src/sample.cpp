#include "performer/sample.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "joint_channels.h"

namespace performer {

void sample(const Skeleton& skeleton, const Motion& motion, double seconds, std::span<JointPose> out) {
  if (out.size() != skeleton.joints.size())
    throw std::invalid_argument("sample: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(skeleton.joints.size()) + " joints");
  if (motion.frames <= 0) {
    for (std::size_t j = 0; j < out.size(); ++j)
      out[j] = JointPose{skeleton.joints[j].offset, {1.0f, 0.0f, 0.0f, 0.0f}};
    return;
  }
  if (!(motion.frame_time > 0.0)) throw std::invalid_argument("sample: frame time must be positive");

  // Position in frames; NaN clamps to the start like any time before it.
  double position = seconds / motion.frame_time;
  const double last = motion.frames - 1;
  if (!(position > 0.0)) position = 0.0;
  if (position > last) position = last;
  // Frame times are rarely exact in binary (1/120 s), so k * frame_time / frame_time can land a hair
  // below k; snapping makes sampling at a frame's time return that frame bit for bit.
  const double nearest = std::round(position);
  if (std::abs(position - nearest) < 1e-6) position = nearest;

  const int f0 = static_cast<int>(std::floor(position));
  const auto t = static_cast<float>(position - f0);
  const std::span<const float> row0 = frame_values(skeleton, motion, f0);
  if (t == 0.0f) {
    for (std::size_t j = 0; j < out.size(); ++j) {
      out[j].translation = detail::joint_translation(skeleton.joints[j], row0);
      out[j].rotation = detail::joint_rotation_quat(skeleton.joints[j], row0);
    }
    return;
  }
  const std::span<const float> row1 = frame_values(skeleton, motion, f0 + 1);
  // Joint by joint, decoding both rows on the fly: no scratch buffers, so the job allocates nothing.
  for (std::size_t j = 0; j < out.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    const JointPose a{detail::joint_translation(joint, row0), detail::joint_rotation_quat(joint, row0)};
    const JointPose b{detail::joint_translation(joint, row1), detail::joint_rotation_quat(joint, row1)};
    out[j] = interpolate(a, b, t);
  }
}

}  // namespace performer
