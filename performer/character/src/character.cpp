#include "performer/character.h"

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "performer/skeleton_skin.h"
#include "performer/skinned_mesh.h"

namespace performer {

namespace {

// The head's streams carried into the body frame once, so the per-frame step (equation 3.20) never
// transforms a DV: the face is deformed where it sits in the rest pose, then skinned with the body.
struct PlacedHead {
  std::vector<glm::vec3> positions, normals;
  std::vector<MorphTarget> targets;
};

PlacedHead place_head(const FaceModel& face, const glm::mat4& placement) {
  const std::size_t n = face.vertex_count();
  const glm::mat3 linear(placement);
  // Computed in double: the placement mixes a large scale (metres to skeleton units) with a rotation,
  // and its inverse is taken once per character.
  const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(linear))));
  PlacedHead head;
  head.positions.resize(n);
  head.normals.resize(n);
  // Per vertex, 1 / |M n|: the neutral normal is made unit again and its normal DVs are scaled by the
  // same factor, so neutral + DV stays proportional to M (n + dn), the transformed target normal.
  // Any per-vertex length cancels in 3.11's renormalisation, while weight 0 reproduces the neutral.
  std::vector<float> normal_scale(n);
  for (std::size_t v = 0; v < n; ++v) {
    head.positions[v] = glm::vec3(placement * glm::vec4(face.positions[v], 1.0f));
    const glm::vec3 m = normal_matrix * face.normals[v];
    const float len = glm::length(m);
    normal_scale[v] = len > 0.0f ? 1.0f / len : 0.0f;
    head.normals[v] = m * normal_scale[v];
  }
  head.targets.reserve(face.targets.size());
  for (const MorphTarget& t : face.targets) {
    MorphTarget placed;
    placed.name = t.name;
    placed.position_deltas.resize(n);
    placed.normal_deltas.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
      placed.position_deltas[v] = linear * t.position_deltas[v];
      placed.normal_deltas[v] = (normal_matrix * t.normal_deltas[v]) * normal_scale[v];
    }
    head.targets.push_back(std::move(placed));
  }
  return head;
}

}  // namespace

Character build_character(const Skeleton& skeleton, const FaceModel& face, const CharacterParams& params) {
  validate_face_model(face, "build_character: face model");
  BodyMesh body = build_body_mesh(skeleton, params.body);
  if (body.attach_joint < 0)
    throw std::invalid_argument("build_character: the skeleton has no joint named '" + params.body.shape.exclude_from +
                                "' to place the head on");
  if (skeleton.joints[static_cast<std::size_t>(body.attach_joint)].end_site)
    throw std::invalid_argument("build_character: the head joint '" + params.body.shape.exclude_from +
                                "' is an end site, which does not move");

  PlacedHead head = place_head(face, body.head_placement);
  const std::size_t body_count = body.mesh.positions.size();
  if (body_count + head.positions.size() > std::size_t{0xffffffffu})
    throw std::invalid_argument("build_character: more vertices than 32-bit indices can name");

  // Merge: body first, head after, head indices offset by the body's vertex count.
  const std::size_t body_triangle_indices = body.mesh.indices.size();
  TriangleMesh merged = std::move(body.mesh);
  merged.positions.insert(merged.positions.end(), head.positions.begin(), head.positions.end());
  merged.normals.insert(merged.normals.end(), head.normals.begin(), head.normals.end());
  merged.indices.reserve(merged.indices.size() + face.indices.size());
  for (const std::uint32_t i : face.indices) merged.indices.push_back(i + static_cast<std::uint32_t>(body_count));

  // Inverse binds belong to the skeleton in output units, the frame the mesh is in.
  Skeleton bind_skeleton = skeleton;
  if (params.body.output_scale != 1.0f)
    for (Joint& j : bind_skeleton.joints) j.offset *= params.body.output_scale;
  // Equation 3.18 over the merged mesh, which the head keeps when SSD is asked for; the body's
  // vertices then get the skeleton-aware weights binding the body alone gives (the same streams,
  // the influence counts made to agree).
  SsdWeightParams head_weights = params.weights;
  head_weights.max_influences = params.body_weights.max_influences;
  SkinnedMesh skinned = bind_to_skeleton(bind_skeleton, std::move(merged), head_weights, params.threads);
  {
    const auto slots = static_cast<std::size_t>(skinned.influences);
    const std::span<const glm::vec3> body_positions(skinned.mesh.positions.data(), body_count);
    const std::span<const std::uint32_t> body_triangles(skinned.mesh.indices.data(), body_triangle_indices);
    body_ssd_weights(body.shape, body_positions, body_triangles, params.body.output_scale, params.body_weights,
                     std::span<std::uint16_t>(skinned.joint_indices.data(), body_count * slots),
                     std::span<float>(skinned.joint_weights.data(), body_count * slots), params.threads);
  }

  Character c;
  c.head_first = body_count;
  c.head_count = face.vertex_count();
  c.influences = skinned.influences;
  c.joint_indices = std::move(skinned.joint_indices);
  c.joint_weights = std::move(skinned.joint_weights);
  c.inverse_bind = std::move(skinned.inverse_bind);
  c.mesh = std::move(skinned.mesh);
  c.head_joint = body.attach_joint;
  c.targets = std::move(head.targets);
  c.head_placement = body.head_placement;
  if (params.head == HeadBinding::rigid) {
    const auto slots = static_cast<std::size_t>(c.influences);
    for (std::size_t v = c.head_first; v < c.head_first + c.head_count; ++v)
      for (std::size_t k = 0; k < slots; ++k) {
        // The padding convention of ssd_weights: unused slots name joint 0 with weight 0.
        c.joint_indices[v * slots + k] = k == 0 ? static_cast<std::uint16_t>(c.head_joint) : 0;
        c.joint_weights[v * slots + k] = k == 0 ? 1.0f : 0.0f;
      }
  }
  return c;
}

std::string character_problem(const Character& c) {
  const std::size_t n = c.mesh.positions.size();
  if (c.mesh.normals.size() != n) return "normals do not match the positions";
  if (c.mesh.indices.size() % 3 != 0) return "index count is not a multiple of 3";
  for (const std::uint32_t i : c.mesh.indices)
    if (i >= n) return "index " + std::to_string(i) + " past the " + std::to_string(n) + " vertices";
  if (c.head_first > n || c.head_count > n - c.head_first) return "head range outside the mesh";
  if (c.influences < 1 || c.influences > kMaxInfluences) return "influences out of range";
  const std::size_t slots = n * static_cast<std::size_t>(c.influences);
  if (c.joint_indices.size() != slots || c.joint_weights.size() != slots) return "skinning streams mis-sized";
  for (const std::uint16_t j : c.joint_indices)
    if (j >= c.inverse_bind.size()) return "joint index " + std::to_string(j) + " has no inverse bind matrix";
  for (const MorphTarget& t : c.targets)
    if (t.position_deltas.size() != c.head_count || t.normal_deltas.size() != c.head_count)
      return "target '" + t.name + "' does not cover the head range";
  return {};
}

}  // namespace performer
