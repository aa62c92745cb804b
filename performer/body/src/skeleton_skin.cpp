#include "performer/skeleton_skin.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "performer/body_weights.h"
#include "performer/local_transforms.h"
#include "performer/skinning.h"
#include "performer/world_transforms.h"

namespace performer {

namespace {

// The skinned mesh's skeleton half: joints in the skeleton's order, translation = offset, identity
// rotation; inverse bind = inverse rest world transform. Weight streams sized, not filled.
SkinnedMesh skin_frame(const Skeleton& skeleton, TriangleMesh mesh, int influences, std::vector<glm::mat4>& world) {
  const std::size_t n = skeleton.joints.size();
  if (n > 65536) throw std::invalid_argument("bind_to_skeleton: more joints than 16-bit indices can name");
  std::vector<glm::mat4> local(n);
  world.resize(n);
  rest_local_transforms(skeleton, local);
  world_transforms(skeleton, local, world);

  SkinnedMesh skinned;
  skinned.joints.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    skinned.joints[j].name = skeleton.joints[j].name;
    skinned.joints[j].parent = skeleton.joints[j].parent;
    skinned.joints[j].translation = skeleton.joints[j].offset;
  }
  skinned.inverse_bind.resize(n);
  inverse_transforms(world, skinned.inverse_bind);
  skinned.influences = influences;
  const std::size_t slots = mesh.positions.size() * static_cast<std::size_t>(std::max(influences, 0));
  skinned.joint_indices.resize(slots);
  skinned.joint_weights.resize(slots);
  skinned.mesh = std::move(mesh);
  return skinned;
}

}  // namespace

SkinnedMesh bind_to_skeleton(const Skeleton& skeleton, TriangleMesh mesh, const SsdWeightParams& params,
                             unsigned threads) {
  std::vector<glm::mat4> world;
  SkinnedMesh skinned = skin_frame(skeleton, std::move(mesh), params.max_influences, world);
  // Weights are computed over the movable joints only, then mapped back to skeleton indices.
  std::vector<glm::vec3> movable;
  std::vector<std::uint16_t> movable_index;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j)
    if (!skeleton.joints[j].end_site) {
      movable.emplace_back(world[j][3]);
      movable_index.push_back(static_cast<std::uint16_t>(j));
    }
  if (movable.empty()) throw std::invalid_argument("bind_to_skeleton: the skeleton has only end sites");
  ssd_weights(skinned.mesh.positions, movable, params, skinned.joint_indices, skinned.joint_weights, threads);
  for (std::uint16_t& index : skinned.joint_indices) index = movable_index[index];
  return skinned;
}

SkinnedMesh bind_body_to_skeleton(const Skeleton& skeleton, const BodyMesh& body, const BodyWeightParams& params,
                                  unsigned threads) {
  // The skeleton in the mesh's units, so that the inverse binds fit the mesh.
  Skeleton scaled = skeleton;
  for (Joint& j : scaled.joints) j.offset *= body.output_scale;
  std::vector<glm::mat4> world;
  SkinnedMesh skinned = skin_frame(scaled, body.mesh, params.max_influences, world);
  body_ssd_weights(body.shape, skinned.mesh.positions, skinned.mesh.indices, body.output_scale, params,
                   skinned.joint_indices, skinned.joint_weights, threads);
  return skinned;
}

}  // namespace performer
