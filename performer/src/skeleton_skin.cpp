#include "performer/skeleton_skin.h"

#include <stdexcept>
#include <utility>
#include <vector>

#include "performer/local_transforms.h"
#include "performer/skinning.h"
#include "performer/world_transforms.h"

namespace performer {

SkinnedMesh bind_to_skeleton(const Skeleton& skeleton, TriangleMesh mesh, const SsdWeightParams& params,
                             unsigned threads) {
  const std::size_t n = skeleton.joints.size();
  if (n > 65536) throw std::invalid_argument("bind_to_skeleton: more joints than 16-bit indices can name");
  std::vector<glm::mat4> local(n), world(n);
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

  // Weights are computed over the movable joints only, then mapped back to skeleton indices.
  std::vector<glm::vec3> movable;
  std::vector<std::uint16_t> movable_index;
  for (std::size_t j = 0; j < n; ++j)
    if (!skeleton.joints[j].end_site) {
      movable.emplace_back(world[j][3]);
      movable_index.push_back(static_cast<std::uint16_t>(j));
    }
  if (movable.empty()) throw std::invalid_argument("bind_to_skeleton: the skeleton has only end sites");
  skinned.influences = params.max_influences;
  const std::size_t slots = mesh.positions.size() * static_cast<std::size_t>(params.max_influences);
  skinned.joint_indices.resize(slots);
  skinned.joint_weights.resize(slots);
  ssd_weights(mesh.positions, movable, params, skinned.joint_indices, skinned.joint_weights, threads);
  for (std::uint16_t& index : skinned.joint_indices) index = movable_index[index];
  skinned.mesh = std::move(mesh);
  return skinned;
}

}  // namespace performer
