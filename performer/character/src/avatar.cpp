#include "performer/avatar.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "performer/body_mesh.h"
#include "performer/skinning.h"

namespace performer {

namespace {

// The vertex shader's slots per vertex (GpuDeformer streams four joints and weights).
constexpr std::size_t kShaderInfluences = 4;

// Vertex v's `slots` influences cut to the strongest kShaderInfluences, renormalised; the slots
// beyond them keep the padding convention (joint 0, weight 0).
void strongest_influences(std::span<const std::uint16_t> joints, std::span<const float> weights,
                          std::span<std::uint16_t> out_joints, std::span<float> out_weights) {
  std::array<std::size_t, kMaxInfluences> order{};
  std::iota(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(joints.size()), std::size_t{0});
  std::stable_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(joints.size()),
                   [&weights](std::size_t a, std::size_t b) { return weights[a] > weights[b]; });
  float sum = 0.0f;
  for (std::size_t k = 0; k < out_joints.size(); ++k) sum += k < joints.size() ? weights[order[k]] : 0.0f;
  for (std::size_t k = 0; k < out_joints.size(); ++k) {
    const bool used = k < joints.size() && sum > 0.0f;
    out_joints[k] = used ? joints[order[k]] : 0;
    out_weights[k] = used ? weights[order[k]] / sum : 0.0f;
  }
}

bool moves(const MorphTarget& t, std::size_t v) {
  return t.position_deltas[v] != glm::vec3(0.0f) || t.normal_deltas[v] != glm::vec3(0.0f);
}

// "mixamorig:LeftArm" -> "leftarm": what two joint names are compared by.
std::string joint_key(std::string_view name) {
  if (const std::size_t colon = name.rfind(':'); colon != std::string_view::npos) name.remove_prefix(colon + 1);
  std::string key(name);
  std::transform(key.begin(), key.end(), key.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return key;
}

// Joint indices with every parent before its children (the hierarchy is known to have no cycle).
std::vector<int> parents_first(const std::vector<int>& parent) {
  std::vector<int> order;
  std::vector<bool> placed(parent.size(), false);
  std::vector<int> chain;
  for (std::size_t start = 0; start < parent.size(); ++start) {
    chain.clear();
    for (int j = static_cast<int>(start); j >= 0 && !placed[static_cast<std::size_t>(j)];
         j = parent[static_cast<std::size_t>(j)])
      chain.push_back(j);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      placed[static_cast<std::size_t>(*it)] = true;
      order.push_back(*it);
    }
  }
  return order;
}

// RMS distance of the points from their centroid.
float spread(std::span<const glm::vec3> points) {
  glm::dvec3 centre(0.0);
  for (const glm::vec3& p : points) centre += glm::dvec3(p);
  centre /= static_cast<double>(points.size());
  double sum = 0.0;
  for (const glm::vec3& p : points) {
    const glm::dvec3 d = glm::dvec3(p) - centre;
    sum += glm::dot(d, d);
  }
  return static_cast<float>(std::sqrt(sum / static_cast<double>(points.size())));
}

}  // namespace

Character avatar_character(const SkinnedMesh& skin, const FaceModel& face) {
  if (const std::string problem = skinned_mesh_problem(skin); !problem.empty())
    throw std::invalid_argument("avatar_character: " + problem);
  const std::size_t n = skin.mesh.positions.size();
  if (face.vertex_count() != n)
    throw std::invalid_argument("avatar_character: the face has " + std::to_string(face.vertex_count()) +
                                " vertices, the skin " + std::to_string(n));
  Character c;
  c.mesh = skin.mesh;
  c.inverse_bind = skin.inverse_bind;
  const auto slots = static_cast<std::size_t>(skin.influences);
  c.influences = static_cast<int>(std::min(slots, kShaderInfluences));
  const auto kept = static_cast<std::size_t>(c.influences);
  c.joint_indices.resize(n * kept);
  c.joint_weights.resize(n * kept);
  for (std::size_t v = 0; v < n; ++v)
    strongest_influences(std::span(skin.joint_indices).subspan(v * slots, slots),
                         std::span(skin.joint_weights).subspan(v * slots, slots),
                         std::span(c.joint_indices).subspan(v * kept, kept),
                         std::span(c.joint_weights).subspan(v * kept, kept));

  // The face range: from the first vertex any target moves. Rigs put the head's vertices anywhere in
  // the mesh, so this can be most of it; it only bounds which vertices read DV streams.
  std::size_t first = n;
  for (const MorphTarget& t : face.targets)
    for (std::size_t v = 0; v < first; ++v)
      if (moves(t, v)) {
        first = v;
        break;
      }
  c.head_first = face.targets.empty() ? n : first;
  c.head_count = n - c.head_first;
  c.targets.reserve(face.targets.size());
  for (const MorphTarget& t : face.targets) {
    const auto from = static_cast<std::ptrdiff_t>(c.head_first);
    c.targets.push_back({t.name,
                         {t.position_deltas.begin() + from, t.position_deltas.end()},
                         {t.normal_deltas.begin() + from, t.normal_deltas.end()}});
  }
  if (const std::string problem = character_problem(c); !problem.empty())
    throw std::invalid_argument("avatar_character: " + problem);
  return c;
}

AvatarRetarget retarget_by_name(const SkinnedMesh& avatar, const Skeleton& skeleton) {
  const std::size_t n = avatar.joints.size();
  AvatarRetarget r;
  std::vector<glm::mat4> local(n);
  r.rest_world.resize(n);
  skin_rest_local_transforms(avatar.joints, local);
  skin_world_transforms(avatar.joints, local, r.rest_world);
  r.parent.resize(n);
  for (std::size_t j = 0; j < n; ++j) r.parent[j] = avatar.joints[j].parent;
  r.order = parents_first(r.parent);

  const std::vector<glm::vec3> skeleton_rest = rest_joint_positions(skeleton);
  r.skeleton_joint.assign(n, -1);
  r.skeleton_rest.assign(n, glm::vec3(0.0f));
  std::vector<glm::vec3> matched_avatar, matched_skeleton;
  for (std::size_t j = 0; j < n; ++j) {
    const std::string key = joint_key(avatar.joints[j].name);
    for (std::size_t b = 0; b < skeleton.joints.size() && r.skeleton_joint[j] < 0; ++b)
      if (joint_key(skeleton.joints[b].name) == key) r.skeleton_joint[j] = static_cast<int>(b);
    if (r.skeleton_joint[j] < 0) {
      r.unmatched.push_back(avatar.joints[j].name);
      continue;
    }
    r.skeleton_rest[j] = skeleton_rest[static_cast<std::size_t>(r.skeleton_joint[j])];
    matched_avatar.emplace_back(r.rest_world[j][3]);
    matched_skeleton.push_back(r.skeleton_rest[j]);
  }
  if (matched_avatar.size() >= 2) {
    const float below = spread(matched_skeleton);
    if (below > 0.0f) r.scale = spread(matched_avatar) / below;
  }
  // Anchors: matched joints with no matched ancestor (the order visits parents first).
  r.anchor.assign(n, false);
  std::vector<bool> matched_above(n, false);  // some ancestor, or the joint itself, is matched
  for (const int j : r.order) {
    const int p = r.parent[static_cast<std::size_t>(j)];
    const bool above = p >= 0 && matched_above[static_cast<std::size_t>(p)];
    const bool matched = r.skeleton_joint[static_cast<std::size_t>(j)] >= 0;
    r.anchor[static_cast<std::size_t>(j)] = matched && !above;
    matched_above[static_cast<std::size_t>(j)] = matched || above;
    if (r.anchor[static_cast<std::size_t>(j)] && r.root < 0) r.root = j;
  }
  return r;
}

void retarget_pose(const AvatarRetarget& r, std::span<const glm::mat4> skeleton_world, std::span<glm::mat4> out) {
  const std::size_t n = r.parent.size();
  if (out.size() != n)
    throw std::invalid_argument("retarget_pose: " + std::to_string(out.size()) + " outputs for " + std::to_string(n) +
                                " avatar joints");
  for (const int b : r.skeleton_joint)
    if (b >= static_cast<int>(skeleton_world.size()))
      throw std::invalid_argument("retarget_pose: " + std::to_string(skeleton_world.size()) +
                                  " skeleton transforms, the avatar follows joint " + std::to_string(b));
  // First each joint's motion from rest, D (world = D * rest world), parents before children: a
  // matched joint turns by its BVH joint's world rotation about where its parent's motion (or, for an
  // anchor, its BVH joint's scaled displacement) takes it; an unmatched joint moves as its parent.
  for (const int signed_j : r.order) {
    const auto j = static_cast<std::size_t>(signed_j);
    const int p = r.parent[j];
    const glm::mat4 parent_motion = p >= 0 ? out[static_cast<std::size_t>(p)] : glm::mat4(1.0f);
    const int b = r.skeleton_joint[j];
    if (b < 0) {
      out[j] = parent_motion;
      continue;
    }
    const glm::mat4& bone = skeleton_world[static_cast<std::size_t>(b)];
    const glm::vec3 rest(r.rest_world[j][3]);
    const glm::vec3 at = r.anchor[j] ? rest + r.scale * (glm::vec3(bone[3]) - r.skeleton_rest[j])
                                     : glm::vec3(parent_motion * glm::vec4(rest, 1.0f));
    const glm::mat3 turn(bone);
    glm::mat4 motion(turn);
    motion[3] = glm::vec4(at - turn * rest, 1.0f);
    out[j] = motion;
  }
  for (std::size_t j = 0; j < n; ++j) out[j] = out[j] * r.rest_world[j];
}

AvatarExport character_avatar(const Character& c, const Skeleton& skeleton) {
  if (const std::string problem = character_problem(c); !problem.empty())
    throw std::invalid_argument("character_avatar: " + problem);
  if (skeleton.joints.size() != c.inverse_bind.size())
    throw std::invalid_argument("character_avatar: " + std::to_string(skeleton.joints.size()) + " joints, " +
                                std::to_string(c.inverse_bind.size()) + " inverse bind matrices");
  AvatarExport out;
  SkinnedMesh& s = out.skin;
  s.mesh = c.mesh;
  s.inverse_bind = c.inverse_bind;
  s.influences = c.influences;
  s.joint_indices = c.joint_indices;
  s.joint_weights = c.joint_weights;
  // Rest offsets in the character's units, from the inverse binds it was bound with: the rest pose
  // has no rotation, so a joint's offset is its rest position less its parent's.
  std::vector<glm::mat4> rest(c.inverse_bind.size());
  inverse_transforms(c.inverse_bind, rest);
  s.joints.resize(skeleton.joints.size());
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    s.joints[j].name = joint.name;
    s.joints[j].parent = joint.parent;
    const glm::vec3 parent_at =
        joint.parent < 0 ? glm::vec3(0.0f) : glm::vec3(rest[static_cast<std::size_t>(joint.parent)][3]);
    s.joints[j].translation = glm::vec3(rest[j][3]) - parent_at;
  }
  const std::size_t n = c.vertex_count();
  for (const MorphTarget& t : c.targets) {
    MorphTarget whole{t.name, std::vector<glm::vec3>(n, glm::vec3(0.0f)), std::vector<glm::vec3>(n, glm::vec3(0.0f))};
    std::copy(t.position_deltas.begin(), t.position_deltas.end(),
              whole.position_deltas.begin() + static_cast<std::ptrdiff_t>(c.head_first));
    std::copy(t.normal_deltas.begin(), t.normal_deltas.end(),
              whole.normal_deltas.begin() + static_cast<std::ptrdiff_t>(c.head_first));
    out.targets.push_back(std::move(whole));
  }
  return out;
}

}  // namespace performer
