#include "performer/local_transforms.h"

#include <stdexcept>
#include <string>

#include "joint_channels.h"

namespace performer {

void local_transforms(const Skeleton& skeleton, std::span<const float> frame_values, std::span<glm::mat4> out) {
  if (out.size() != skeleton.joints.size())
    throw std::invalid_argument("local_transforms: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(skeleton.joints.size()) + " joints");
  if (frame_values.size() != static_cast<std::size_t>(channel_count(skeleton)))
    throw std::invalid_argument("local_transforms: frame has " + std::to_string(frame_values.size()) +
                                " values, the skeleton " + std::to_string(channel_count(skeleton)) + " channels");
  for (std::size_t j = 0; j < out.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    const glm::mat3 r = detail::joint_rotation_matrix(joint, frame_values);
    // Written out rather than glm::translate(...) * mat4(r): the product of a translation and a
    // rotation is just the rotation with the translation as its last column.
    glm::mat4& m = out[j];
    m = glm::mat4(r);
    m[3] = glm::vec4(detail::joint_translation(joint, frame_values), 1.0f);
  }
}

void rest_local_transforms(const Skeleton& skeleton, std::span<glm::mat4> out) {
  if (out.size() != skeleton.joints.size())
    throw std::invalid_argument("rest_local_transforms: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(skeleton.joints.size()) + " joints");
  for (std::size_t j = 0; j < out.size(); ++j) {
    out[j] = glm::mat4(1.0f);
    out[j][3] = glm::vec4(skeleton.joints[j].offset, 1.0f);
  }
}

}  // namespace performer
