#include "performer/skinned_mesh.h"

#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "performer/ssd_weights.h"

namespace performer {

void skin_rest_local_transforms(std::span<const SkinJoint> joints, std::span<glm::mat4> out) {
  if (out.size() != joints.size())
    throw std::invalid_argument("skin_rest_local_transforms: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(joints.size()) + " joints");
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const SkinJoint& joint = joints[j];
    out[j] =
        glm::scale(glm::translate(glm::mat4(1.0f), joint.translation) * glm::mat4_cast(joint.rotation), joint.scale);
  }
}

void skin_world_transforms(std::span<const SkinJoint> joints, std::span<const glm::mat4> local,
                           std::span<glm::mat4> out) {
  const std::size_t n = joints.size();
  if (local.size() != n || out.size() != n)
    throw std::invalid_argument("skin_world_transforms: " + std::to_string(local.size()) + " locals and " +
                                std::to_string(out.size()) + " outputs for " + std::to_string(n) + " joints");
  // glTF does not order joints parents-first, so each joint is resolved after the chain above it:
  // walk up to a finished joint (or a root), then fill the chain in on the way down.
  enum : std::uint8_t { kTodo, kOnPath, kDone };
  std::vector<std::uint8_t> state(n, kTodo);
  std::vector<std::size_t> chain;
  for (std::size_t start = 0; start < n; ++start) {
    chain.clear();
    for (std::size_t j = start;;) {
      if (state[j] == kDone) break;
      if (state[j] == kOnPath)
        throw std::invalid_argument("skin_world_transforms: joint " + std::to_string(j) + " is its own ancestor");
      state[j] = kOnPath;
      chain.push_back(j);
      const int parent = joints[j].parent;
      if (parent < 0) break;
      if (static_cast<std::size_t>(parent) >= n)
        throw std::invalid_argument("skin_world_transforms: joint " + std::to_string(j) + " has parent " +
                                    std::to_string(parent) + " of " + std::to_string(n) + " joints");
      j = static_cast<std::size_t>(parent);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const SkinJoint& joint = joints[*it];
      const glm::mat4 base = joint.parent < 0 ? joint.above : out[static_cast<std::size_t>(joint.parent)] * joint.above;
      out[*it] = base * local[*it];
      state[*it] = kDone;
    }
  }
}

std::string skinned_mesh_problem(const SkinnedMesh& s) {
  const std::size_t vertices = s.mesh.positions.size();
  if (!s.mesh.normals.empty() && s.mesh.normals.size() != vertices)
    return std::to_string(s.mesh.normals.size()) + " normals for " + std::to_string(vertices) + " positions";
  if (s.mesh.indices.size() % 3 != 0)
    return "index count " + std::to_string(s.mesh.indices.size()) + " is not a multiple of 3";
  for (const std::uint32_t i : s.mesh.indices)
    if (i >= vertices) return "vertex index " + std::to_string(i) + " of " + std::to_string(vertices) + " vertices";
  if (s.inverse_bind.size() != s.joints.size())
    return std::to_string(s.inverse_bind.size()) + " inverse bind matrices for " + std::to_string(s.joints.size()) +
           " joints";
  for (std::size_t j = 0; j < s.joints.size(); ++j)
    if (s.joints[j].parent < -1 || s.joints[j].parent >= static_cast<int>(s.joints.size()))
      return "joint " + std::to_string(j) + " has parent " + std::to_string(s.joints[j].parent);
  if (s.influences < 1 || s.influences > kMaxInfluences) return "influences " + std::to_string(s.influences);
  const std::size_t slots = vertices * static_cast<std::size_t>(s.influences);
  if (s.joint_indices.size() != slots || s.joint_weights.size() != slots)
    return std::to_string(s.joint_indices.size()) + " joint indices and " + std::to_string(s.joint_weights.size()) +
           " weights for " + std::to_string(slots) + " slots";
  for (const std::uint16_t j : s.joint_indices)
    if (j >= s.joints.size())
      return "joint index " + std::to_string(j) + " of " + std::to_string(s.joints.size()) + " joints";
  return {};
}

}  // namespace performer
