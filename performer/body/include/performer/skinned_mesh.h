// A mesh bound to a joint hierarchy, as glTF 2.0 skins store it (gltf_skin.h reads and writes it)
// and as the skinning job consumes it: the per-vertex joint indices and weights, the per-joint
// inverse bind matrices and the joints' rest transforms are exactly SkinningJob's streams and
// skinning_matrices()' inputs, so nothing is converted between file and shader.
//
// Posing, as glTF defines it: world[j] = world[parent] * above[j] * local[j] (the roots' parent
// term is the identity), then skinning_matrices(world, inverse_bind) gives the matrices of
// equation 3.17, and skin() applies them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "performer/triangle_mesh.h"

namespace performer {

struct SkinJoint {
  std::string name;
  int parent = -1;  // index into SkinnedMesh::joints; -1 when no ancestor node is a joint
  // Rest local transform, translation * rotation * scale, as a glTF node stores it.
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  // Product of the transforms of the nodes between the parent joint (or the scene root) and this
  // joint that are not joints themselves; the identity in most files.
  glm::mat4 above{1.0f};
};

struct SkinnedMesh {
  TriangleMesh mesh;                         // in the bind pose
  std::vector<SkinJoint> joints;             // the skin's joints, in the file's order
  std::vector<glm::mat4> inverse_bind;       // one per joint: bind-pose world transform, inverted
  int influences = 4;                        // slots per vertex
  std::vector<std::uint16_t> joint_indices;  // positions.size() * influences, indices into joints
  std::vector<float> joint_weights;          // same size, each vertex's slots summing to 1
};

// out[j] = translate(t) * mat4(r) * scale(s) of joints[j]. Sizes must match.
void skin_rest_local_transforms(std::span<const SkinJoint> joints, std::span<glm::mat4> out);

// World transforms from local ones along the joint hierarchy (see the top of this file). Parents may
// come after their children, as glTF allows. Throws std::invalid_argument on size mismatches, a
// parent index out of range, or a cycle. `out` may not alias `local`.
void skin_world_transforms(std::span<const SkinJoint> joints, std::span<const glm::mat4> local,
                           std::span<glm::mat4> out);

// Streams consistent: sizes agree, indices in range, influences 1 to kMaxInfluences. Returns the
// first problem found, empty when there is none.
std::string skinned_mesh_problem(const SkinnedMesh& skinned);

}  // namespace performer
