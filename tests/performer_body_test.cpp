// Tests for the performer's body (thesis 3.5-3.6): the mesh generated around a skeleton
// (body_shape, marching_cubes, mesh_smooth, body_mesh), binding it to the skeleton
// (skeleton_skin), and skinned meshes in glTF 2.0 (gltf_skin, skinned_mesh).

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shared_assets.h"
#include "support/skeleton_joints.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "performer/body_mesh.h"
#include "performer/body_shape.h"
#include "performer/bvh.h"
#include "performer/gltf_skin.h"
#include "performer/local_transforms.h"
#include "performer/marching_cubes.h"
#include "performer/mesh_normals.h"
#include "performer/mesh_smooth.h"
#include "performer/scalar_grid.h"
#include "performer/skeleton.h"
#include "performer/skeleton_skin.h"
#include "performer/skinned_mesh.h"
#include "performer/skinning.h"
#include "performer/world_transforms.h"

namespace fs = std::filesystem;
using performer::BodyMesh;
using performer::BodyMeshParams;
using performer::Skeleton;
using performer::SkinnedMesh;
using performer::TriangleMesh;

namespace {

// --- Mesh checks --------------------------------------------------------------------------------

struct EdgeReport {
  std::size_t edges = 0;
  std::size_t not_in_two = 0;   // undirected edges used by other than exactly two triangles
  std::size_t not_opposed = 0;  // directed edges without exactly one opposite partner
  std::size_t degenerate = 0;   // triangles repeating a vertex
};

// A closed, consistently oriented 2-manifold uses every edge in exactly two triangles, once in each
// direction.
EdgeReport edge_report(const TriangleMesh& mesh) {
  EdgeReport r;
  std::unordered_map<std::uint64_t, int> directed;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) ++r.degenerate;
    for (int e = 0; e < 3; ++e) ++directed[key(v[e], v[(e + 1) % 3])];
  }
  for (const auto& [k, count] : directed) {
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k);
    const auto back = directed.find(key(b, a));
    const int opposite = back == directed.end() ? 0 : back->second;
    if (count != 1 || opposite != 1) ++r.not_opposed;
    if (a < b || opposite == 0) {
      ++r.edges;
      if (count + opposite != 2) ++r.not_in_two;
    }
  }
  return r;
}

double signed_volume(const TriangleMesh& mesh) {
  double v = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

// Generalised winding number: the solid angle the surface subtends at p over 4 pi (Van Oosterom and
// Strackee's formula per triangle). About 1 inside a closed outward mesh, 0 outside, and robust to
// where p sits relative to edges, unlike ray parity.
double winding_number(const TriangleMesh& mesh, const glm::vec3& p) {
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = glm::dvec3(mesh.positions[mesh.indices[t]]) - glm::dvec3(p);
    const glm::dvec3 b = glm::dvec3(mesh.positions[mesh.indices[t + 1]]) - glm::dvec3(p);
    const glm::dvec3 c = glm::dvec3(mesh.positions[mesh.indices[t + 2]]) - glm::dvec3(p);
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = glm::dot(a, glm::cross(b, c));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * std::numbers::pi);
}

void expect_closed_outward(const TriangleMesh& mesh, const std::string& label) {
  ASSERT_FALSE(mesh.indices.empty()) << label;
  ASSERT_EQ(mesh.indices.size() % 3, 0u) << label;
  for (const std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size()) << label;
  const EdgeReport r = edge_report(mesh);
  EXPECT_EQ(r.degenerate, 0u) << label;
  EXPECT_EQ(r.not_in_two, 0u) << label << ": " << r.edges << " edges";
  EXPECT_EQ(r.not_opposed, 0u) << label << ": inconsistently oriented edges";
  EXPECT_GT(signed_volume(mesh), 0.0) << label << ": faces point inward";
}

void expect_unit_normals(const TriangleMesh& mesh, const std::string& label) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << label;
  for (std::size_t v = 0; v < mesh.normals.size(); ++v)
    ASSERT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-4f) << label << " vertex " << v;
  // And outward: a vertex normal agrees with the (outward) triangles around it.
  std::vector<glm::vec3> faces(mesh.positions.size());
  performer::area_weighted_normals(mesh.positions, mesh.indices, faces);
  std::size_t disagree = 0;
  for (std::size_t v = 0; v < faces.size(); ++v) disagree += glm::dot(faces[v], mesh.normals[v]) <= 0.0f ? 1 : 0;
  EXPECT_EQ(disagree, 0u) << label;
}

// --- Skeletons ------------------------------------------------------------------------------------

using test_support::joint;

// Root, a joint 10 up, an end site 10 further: two bones in a straight line.
Skeleton two_bone_skeleton() {
  Skeleton sk;
  sk.joints.push_back(joint("root", -1, {0, 0, 0}));
  sk.joints.push_back(joint("mid", 0, {0, 10, 0}));
  sk.joints.push_back(joint("mid_end", 1, {0, 10, 0}, true));
  return sk;
}

std::vector<glm::mat4> rest_world(const Skeleton& sk) {
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::rest_local_transforms(sk, local);
  performer::world_transforms(sk, local, world);
  return world;
}

// Skins `skinned` with the given joint world transforms and returns the new positions and normals.
TriangleMesh pose(const SkinnedMesh& skinned, const std::vector<glm::mat4>& world) {
  std::vector<glm::mat4> matrices(world.size());
  performer::skinning_matrices(world, skinned.inverse_bind, matrices);
  TriangleMesh out;
  out.positions.resize(skinned.mesh.positions.size());
  out.normals.resize(skinned.mesh.normals.size());
  out.indices = skinned.mesh.indices;
  performer::SkinningJob job;
  job.influences = skinned.influences;
  job.matrices = matrices;
  job.joint_indices = skinned.joint_indices;
  job.joint_weights = skinned.joint_weights;
  job.in_positions = skinned.mesh.positions;
  job.out_positions = out.positions;
  job.in_normals = skinned.mesh.normals;
  job.out_normals = out.normals;
  EXPECT_TRUE(job.valid());
  performer::skin(job);
  return out;
}

void expect_same_mesh(const TriangleMesh& a, const TriangleMesh& b, float tolerance, const std::string& label) {
  ASSERT_EQ(a.positions.size(), b.positions.size()) << label;
  ASSERT_EQ(a.normals.size(), b.normals.size()) << label;
  float worst = 0.0f, worst_normal = 0.0f;
  for (std::size_t v = 0; v < a.positions.size(); ++v) {
    worst = std::max(worst, glm::distance(a.positions[v], b.positions[v]));
    if (!a.normals.empty()) worst_normal = std::max(worst_normal, glm::distance(a.normals[v], b.normals[v]));
  }
  EXPECT_LE(worst, tolerance) << label << ": positions";
  EXPECT_LE(worst_normal, 1e-4f) << label << ": normals";
}

// --- The CMU skeletons --------------------------------------------------------------------------

// A valid binding: the streams agree, every vertex's weights are non-negative, sum to 1 and name
// no end site, and the rest pose gives the mesh back.
void expect_bound_to(const SkinnedMesh& skinned, const Skeleton& sk, const TriangleMesh& mesh) {
  ASSERT_EQ(performer::skinned_mesh_problem(skinned), "");
  const auto slots = static_cast<std::size_t>(skinned.influences);
  for (std::size_t v = 0; v < skinned.mesh.positions.size(); ++v) {
    float sum = 0.0f;
    for (std::size_t k = 0; k < slots; ++k) {
      const float w = skinned.joint_weights[v * slots + k];
      ASSERT_GE(w, 0.0f);
      sum += w;
      if (w > 0.0f) {
        ASSERT_FALSE(sk.joints[skinned.joint_indices[v * slots + k]].end_site) << "vertex " << v;
      }
    }
    ASSERT_NEAR(sum, 1.0f, 1e-5f) << "vertex " << v;
  }
  expect_same_mesh(pose(skinned, rest_world(sk)), mesh, 1e-4f, "rest pose");
}

struct CmuBody {
  performer::Bvh bvh;
  BodyMesh body;
  double build_ms = 0.0;
};

// Built once per file and shared by the tests below: a build is the expensive part.
const CmuBody& cmu_body(const std::string& name) {
  static std::map<std::string, std::unique_ptr<CmuBody>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<CmuBody>();
    slot->bvh = performer::read_bvh(test_support::bvh_asset(name));
    const auto start = std::chrono::steady_clock::now();
    slot->body = performer::build_body_mesh(slot->bvh.skeleton);
    slot->build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  return *slot;
}

class CmuBodyTest : public ::testing::TestWithParam<const char*> {};

#define REQUIRE_CMU(name) REQUIRE_SHARED_FILE(test_support::bvh_asset(name))

TEST_P(CmuBodyTest, ClosedManifoldOutwardWithUnitNormals) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const TriangleMesh& mesh = cmu.body.mesh;
  std::cout << GetParam() << ": " << mesh.positions.size() << " vertices, " << mesh.indices.size() / 3
            << " triangles, built in " << cmu.build_ms << " ms\n";
  // The thesis' character has about 15,000 vertices (table 3.8).
  EXPECT_GE(mesh.positions.size(), 10000u);
  EXPECT_LE(mesh.positions.size(), 20000u);
  expect_closed_outward(mesh, GetParam());
  expect_unit_normals(mesh, GetParam());
}

TEST_P(CmuBodyTest, JointsLieInside) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const Skeleton& sk = cmu.bvh.skeleton;
  const int head = performer::find_joint(sk, "Head");
  ASSERT_GE(head, 0);
  const std::vector<glm::mat4> world = rest_world(sk);
  int checked = 0;
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    if (sk.joints[j].end_site || sk.joints[j].parent == head) continue;  // the head's own bones are left out
    const glm::vec3 p(world[j][3]);
    EXPECT_NEAR(winding_number(cmu.body.mesh, p), 1.0, 1e-3) << sk.joints[j].name;
    ++checked;
  }
  EXPECT_EQ(checked, 31);
  // And outside: well beside the hips, and above where the head goes.
  EXPECT_NEAR(winding_number(cmu.body.mesh, glm::vec3(world[0][3]) + glm::vec3(0, 0, 6)), 0.0, 1e-3);
  EXPECT_NEAR(
      winding_number(cmu.body.mesh, glm::vec3(world[static_cast<std::size_t>(head)][3]) + glm::vec3(0, 1.5f, 0)), 0.0,
      1e-3);
}

TEST_P(CmuBodyTest, HeadLeftOutAndItsJointReported) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const Skeleton& sk = cmu.bvh.skeleton;
  const int head = performer::find_joint(sk, "Head");
  ASSERT_EQ(cmu.body.attach_joint, head);
  const std::vector<glm::mat4> world = rest_world(sk);
  const glm::mat4 expected = world[static_cast<std::size_t>(head)];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(cmu.body.attach_rest_world[c][r], expected[c][r], 1e-5f);
  // The head model (metres) is scaled into skeleton units and its neck base put on the joint.
  const glm::vec4 neck_base = cmu.body.head_placement * glm::vec4(0, 0, 0, 1);
  const glm::vec4 crown = cmu.body.head_placement * glm::vec4(0, 0.23f, 0, 1);
  EXPECT_NEAR(glm::distance(glm::vec3(neck_base), glm::vec3(expected[3])), 0.0f, 1e-5f);
  EXPECT_NEAR(crown.y - neck_base.y, 0.23f / performer::kCmuMetersPerUnit, 1e-3f);
  // No bone from the head joint was grown: the mesh ends at the neck's round cap.
  for (const performer::BoneCapsule& c : cmu.body.shape.capsules) EXPECT_NE(c.parent, head);
  float top = -1e9f;
  for (const glm::vec3& p : cmu.body.mesh.positions) top = std::max(top, p.y);
  float neck = 0.0f;
  for (const performer::BoneCapsule& c : cmu.body.shape.capsules)
    if (c.joint == head) neck = c.radius_b;
  EXPECT_GT(neck, 0.0f);
  EXPECT_LT(top, expected[3].y + neck + cmu.body.cell);
  EXPECT_LT(top, world[static_cast<std::size_t>(performer::find_joint(sk, "Head_end"))][3].y);
}

TEST_P(CmuBodyTest, SsdWeightsValidAndRestPoseReproducesMesh) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const Skeleton& sk = cmu.bvh.skeleton;
  const SkinnedMesh skinned = performer::bind_to_skeleton(sk, cmu.body.mesh);
  expect_bound_to(skinned, sk, cmu.body.mesh);

  // A frame of the motion carries the skin along with the skeleton: every vertex stays within the
  // posed joints' bounds, widened by the thickest capsule and a margin.
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::local_transforms(sk, performer::frame_values(sk, cmu.bvh.motion, cmu.bvh.motion.frames / 2), local);
  performer::world_transforms(sk, local, world);
  const TriangleMesh posed = pose(skinned, world);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::mat4& m : world) {
    lo = glm::min(lo, glm::vec3(m[3]));
    hi = glm::max(hi, glm::vec3(m[3]));
  }
  float thickest = 0.0f;
  for (const performer::BoneCapsule& c : cmu.body.shape.capsules)
    thickest = std::max({thickest, c.radius_a, c.radius_b});
  const glm::vec3 margin(thickest + 1.0f);
  for (std::size_t v = 0; v < posed.positions.size(); ++v) {
    const glm::vec3 p = posed.positions[v];
    ASSERT_TRUE(glm::all(glm::greaterThan(p, lo - margin)) && glm::all(glm::lessThan(p, hi + margin)))
        << "vertex " << v;
  }
}

// How the skin's edges stretch over a clip: every 25th frame posed, each edge's length against the
// rest pose.
struct Stretch {
  int frames = 0;
  double longest = 1.0;  // largest posed / rest edge length over all frames
  int longest_frame = 0;
  double share = 0.0;     // largest share of edges beyond twice their rest length in any frame
  double shortest = 1.0;  // smallest posed / rest (creases of bent joints)
};

Stretch stretch_in_motion(const CmuBody& cmu, const SkinnedMesh& skinned) {
  const Skeleton& sk = cmu.bvh.skeleton;
  const TriangleMesh& rest = cmu.body.mesh;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t t = 0; t < rest.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = rest.indices[t + e], b = rest.indices[t + (e + 1) % 3];
      if (a < b) edges.emplace_back(a, b);  // each edge once (its other triangle has b, a)
    }
  Stretch s;
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  for (int f = 0; f < cmu.bvh.motion.frames; f += 25, ++s.frames) {
    performer::local_transforms(sk, performer::frame_values(sk, cmu.bvh.motion, f), local);
    performer::world_transforms(sk, local, world);
    const TriangleMesh posed = pose(skinned, world);
    std::size_t beyond_two = 0;
    for (const auto& [a, b] : edges) {
      const double ratio =
          glm::length(posed.positions[a] - posed.positions[b]) / glm::length(rest.positions[a] - rest.positions[b]);
      if (ratio > 2.0) ++beyond_two;
      if (ratio > s.longest) s.longest = ratio, s.longest_frame = f;
      s.shortest = std::min(s.shortest, ratio);
    }
    s.share = std::max(s.share, static_cast<double>(beyond_two) / static_cast<double>(edges.size()));
  }
  return s;
}

// The skin holds together in motion: over every 25th frame of the clip, at most 0.1 % of the edges
// grow beyond twice their rest length, and none beyond 4 times. Squashing in the crease of a bent
// knee or elbow is linear blend skinning's known volume loss (equation 3.17 as the thesis keeps
// it), reported, not bounded. Equation 3.18 alone, distance weights over every joint, fails: it
// blends bones that are close in space but far apart on the skeleton, and arm and leg skin
// stretches into sheets across the torso; the same measure must see that.
TEST_P(CmuBodyTest, SkinHoldsTogetherInMotion) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const Skeleton& sk = cmu.bvh.skeleton;
  const SkinnedMesh skinned = performer::bind_body_to_skeleton(sk, cmu.body);
  expect_bound_to(skinned, sk, cmu.body.mesh);

  const Stretch s = stretch_in_motion(cmu, skinned);
  std::printf(
      "%s, skeleton-aware weights: %d frames, longest edge %.2fx its rest length (frame %d), at most %.3f %% "
      "of edges beyond 2x; shortest %.3fx\n",
      GetParam(), s.frames, s.longest, s.longest_frame, 100.0 * s.share, s.shortest);
  EXPECT_LE(s.share, 0.001);
  EXPECT_LT(s.longest, 4.0);

  const Stretch distance_only = stretch_in_motion(cmu, performer::bind_to_skeleton(sk, cmu.body.mesh));
  std::printf("%s, equation 3.18 alone: longest edge %.2fx (frame %d), at most %.3f %% of edges beyond 2x\n",
              GetParam(), distance_only.longest, distance_only.longest_frame, 100.0 * distance_only.share);
  EXPECT_GT(distance_only.longest, 4.0);
  EXPECT_GT(distance_only.share, 0.001);
}

TEST_P(CmuBodyTest, ExportsToGltfAndPosesTheSame) {
  REQUIRE_CMU(GetParam());
  const CmuBody& cmu = cmu_body(GetParam());
  const Skeleton& sk = cmu.bvh.skeleton;
  const SkinnedMesh skinned = performer::bind_to_skeleton(sk, cmu.body.mesh);
  test_support::ScratchDir dir("performer_body");
  const fs::path path = dir / "character.glb";
  performer::write_gltf_skinned(path, skinned);
  const SkinnedMesh loaded = performer::read_gltf_skinned(path);
  ASSERT_EQ(loaded.joints.size(), sk.joints.size());
  // BVH locals drive the glTF joints directly: same joints, same order.
  std::vector<glm::mat4> local(sk.joints.size()), bvh_world(sk.joints.size()), gltf_world(sk.joints.size());
  performer::local_transforms(sk, performer::frame_values(sk, cmu.bvh.motion, 100), local);
  performer::world_transforms(sk, local, bvh_world);
  performer::skin_world_transforms(loaded.joints, local, gltf_world);
  expect_same_mesh(pose(loaded, gltf_world), pose(skinned, bvh_world), 1e-4f, "frame 100");
}

INSTANTIATE_TEST_SUITE_P(Cmu, CmuBodyTest, ::testing::Values("cmu_131_01.bvh", "cmu_131_02.bvh", "cmu_131_03.bvh"),
                         [](const auto& info) { return std::string(info.param).substr(4, 6); });

// --- Body shape and mesh on hand-made skeletons --------------------------------------------------

// Skeleton-aware weights on a straight two-bone limb: skin by the middle of each bone moves with
// that bone alone, skin at the joint with both, blended smoothly along the limb.
TEST(BodyWeights, EachBoneOwnsItsMiddleAndTheJointBlends) {
  const Skeleton sk = two_bone_skeleton();
  BodyMeshParams params;
  params.shape.exclude_from.clear();
  params.grid_cells = 48;
  const BodyMesh body = performer::build_body_mesh(sk, params);
  const SkinnedMesh skinned = performer::bind_body_to_skeleton(sk, body);
  const auto slots = static_cast<std::size_t>(skinned.influences);
  auto weight_of = [&](std::size_t v, int joint) {
    float w = 0.0f;
    for (std::size_t k = 0; k < slots; ++k)
      if (skinned.joint_indices[v * slots + k] == joint) w += skinned.joint_weights[v * slots + k];
    return w;
  };
  float previous_height = -1.0f, previous_root = 2.0f;
  std::vector<std::pair<float, float>> by_height;  // (height, weight of the root joint)
  for (std::size_t v = 0; v < body.mesh.positions.size(); ++v) {
    const float y = body.mesh.positions[v].y, root = weight_of(v, 0);
    EXPECT_NEAR(root + weight_of(v, 1), 1.0f, 1e-5f);
    if (y > 1.5f && y < 4.0f) {
      EXPECT_GT(root, 0.9f) << "lower bone's middle, vertex " << v;
    }
    if (y > 16.0f && y < 18.5f) {
      EXPECT_LT(root, 0.1f) << "upper bone's middle, vertex " << v;
    }
    if (std::abs(y - 10.0f) < 0.5f) {
      EXPECT_NEAR(root, 0.5f, 0.2f) << "at the joint, vertex " << v;
    }
    by_height.emplace_back(y, root);
  }
  // Smooth along the limb: averaged over thin slices, the root's weight never rises with height.
  std::sort(by_height.begin(), by_height.end());
  for (float y0 = 1.0f; y0 < 19.0f; y0 += 1.0f) {
    float sum = 0.0f;
    int n = 0;
    for (const auto& [y, w] : by_height)
      if (y >= y0 && y < y0 + 1.0f) sum += w, ++n;
    if (n == 0) continue;
    const float mean = sum / static_cast<float>(n);
    EXPECT_LE(mean, previous_root + 0.02f) << "slice at " << y0;
    previous_root = mean, previous_height = y0;
  }
  EXPECT_GT(previous_height, 15.0f);

  performer::BodyWeightParams bad;
  bad.max_influences = 0;
  EXPECT_THROW(performer::bind_body_to_skeleton(sk, body, bad), std::invalid_argument);
  bad = {};
  bad.smoothing_steps = -1;
  EXPECT_THROW(performer::bind_body_to_skeleton(sk, body, bad), std::invalid_argument);
  bad = {};
  bad.falloff = -1.0f;
  EXPECT_THROW(performer::bind_body_to_skeleton(sk, body, bad), std::invalid_argument);
}

TEST(BodyShape, RadiiFollowTheCarriedLength) {
  const Skeleton sk = two_bone_skeleton();
  const auto joints = performer::rest_joint_positions(sk);
  performer::BodyShapeParams p;
  p.exclude_from.clear();
  const performer::BodyShape shape = performer::body_shape(sk, joints, p);
  ASSERT_EQ(shape.capsules.size(), 2u);
  const float size = 20.0f, scale = p.thickness * size;
  // Bone 1 carries both bones (all of the length), bone 2 half; the tip carries nothing and gets
  // the floor radius.
  EXPECT_NEAR(shape.capsules[0].radius_a, scale, 1e-5f);
  EXPECT_NEAR(shape.capsules[0].radius_b, scale * std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(shape.capsules[1].radius_a, scale * std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(shape.capsules[1].radius_b, p.min_radius * size, 1e-5f);
  EXPECT_EQ(shape.related, (std::vector<std::uint8_t>{1, 1, 1, 1}));
  EXPECT_FLOAT_EQ(shape.blend, p.blend * size);
}

TEST(BodyShape, ZeroLengthBonesSkippedAndHeadExcluded) {
  Skeleton sk;
  sk.joints.push_back(joint("Hips", -1, {0, 0, 0}));
  sk.joints.push_back(joint("lowerback", 0, {0, 0, 0}));  // zero length, as in the CMU files
  sk.joints.push_back(joint("Neck", 1, {0, 8, 0}));
  sk.joints.push_back(joint("Head", 2, {0, 2, 0}));
  sk.joints.push_back(joint("Head_end", 3, {0, 2, 0}, true));
  const auto joints = performer::rest_joint_positions(sk);
  performer::BodyShapeParams p;
  const performer::BodyShape shape = performer::body_shape(sk, joints, p);
  ASSERT_EQ(shape.capsules.size(), 2u);  // lowerback -> Neck and Neck -> Head
  EXPECT_EQ(shape.capsules[0].joint, 2);
  EXPECT_EQ(shape.capsules[1].joint, 3);
  // Into the attach joint the neck keeps its width, at least neck_radius.
  EXPECT_FLOAT_EQ(shape.capsules[1].radius_b, shape.capsules[1].radius_a);
  EXPECT_GE(shape.capsules[1].radius_a, p.neck_radius * 12.0f - 1e-5f);
  p.exclude_from.clear();
  EXPECT_EQ(performer::body_shape(sk, joints, p).capsules.size(), 3u);
  p.exclude_from = "NoSuchJoint";
  EXPECT_EQ(performer::body_shape(sk, joints, p).capsules.size(), 3u);
}

TEST(BodyShape, UnrelatedCapsulesAreKeptApart) {
  // Two parallel capsules of radius 1, 1.5 apart: they overlap around x = 0.
  performer::BodyShape shape;
  performer::BoneCapsule a, b;
  a.a = {-0.75f, 0, 0};
  a.b = {-0.75f, 10, 0};
  b.a = {0.75f, 0, 0};
  b.b = {0.75f, 10, 0};
  a.radius_a = a.radius_b = b.radius_a = b.radius_b = 1.0f;
  shape.capsules = {a, b};
  shape.blend = 0.2f;
  shape.separation = 0.3f;
  const glm::vec3 between(0, 5, 0), inside_a(-0.75f, 5, 0), inside_b(0.75f, 5, 0);
  shape.related = {1, 1, 1, 1};
  EXPECT_LT(performer::body_field(shape, between), 0.0f) << "related capsules merge";
  shape.related = {1, 0, 0, 1};
  EXPECT_GT(performer::body_field(shape, between), 0.0f) << "unrelated capsules get a gap";
  EXPECT_LT(performer::body_field(shape, inside_a), 0.0f);
  EXPECT_LT(performer::body_field(shape, inside_b), 0.0f);
  // Away from the gap the field is the plain union: exact on each capsule's far side.
  EXPECT_NEAR(performer::body_field(shape, glm::vec3(-2.75f, 5, 0)), 1.0f, 1e-5f);
  shape.separation = 0.0f;
  EXPECT_LT(performer::body_field(shape, between), 0.0f) << "separation 0 turns the gap off";
}

TEST(BodyMesh, TwoBoneSurfaceAtTheCapsuleRadius) {
  const Skeleton sk = two_bone_skeleton();
  BodyMeshParams params;
  params.shape.exclude_from.clear();
  const BodyMesh body = performer::build_body_mesh(sk, params);
  expect_closed_outward(body.mesh, "two bones");
  expect_unit_normals(body.mesh, "two bones");
  ASSERT_EQ(body.shape.capsules.size(), 2u);
  EXPECT_EQ(body.attach_joint, -1);
  // Away from the joint, where the smooth union does not reach, every vertex lies on its capsule.
  int checked = 0;
  float worst = 0.0f;
  for (const glm::vec3& p : body.mesh.positions) {
    const float d0 = performer::capsule_field(body.shape.capsules[0], p);
    const float d1 = performer::capsule_field(body.shape.capsules[1], p);
    if (std::abs(d0 - d1) < 2.0f * body.shape.blend) continue;
    worst = std::max(worst, std::abs(std::min(d0, d1)));
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 0.25f * body.cell) << "cell " << body.cell;
  // Joints inside; output_scale scales the mesh.
  for (const glm::vec3& p : performer::rest_joint_positions(sk)) EXPECT_NEAR(winding_number(body.mesh, p), 1.0, 1e-3);
  params.output_scale = 0.5f;
  const BodyMesh half = performer::build_body_mesh(sk, params);
  ASSERT_EQ(half.mesh.positions.size(), body.mesh.positions.size());
  for (std::size_t v = 0; v < half.mesh.positions.size(); v += 97)
    EXPECT_NEAR(glm::distance(half.mesh.positions[v], 0.5f * body.mesh.positions[v]), 0.0f, 1e-5f);
}

TEST(BodyMesh, GridCellsSetTheDetail) {
  const Skeleton sk = two_bone_skeleton();
  BodyMeshParams params;
  params.grid_cells = 40;
  const std::size_t coarse = performer::build_body_mesh(sk, params).mesh.positions.size();
  params.grid_cells = 80;
  const std::size_t fine = performer::build_body_mesh(sk, params).mesh.positions.size();
  // Vertices grow with the square of the resolution.
  EXPECT_GT(fine, 3 * coarse);
  EXPECT_LT(fine, 5 * coarse);
}

TEST(BodyMesh, RejectsBadInput) {
  Skeleton only_root;
  only_root.joints.push_back(joint("root", -1, {0, 0, 0}));
  EXPECT_THROW(performer::build_body_mesh(only_root), std::invalid_argument);
  BodyMeshParams params;
  params.grid_cells = 2;
  EXPECT_THROW(performer::build_body_mesh(two_bone_skeleton(), params), std::invalid_argument);
  params = {};
  params.shape.thickness = 0.0f;
  EXPECT_THROW(performer::build_body_mesh(two_bone_skeleton(), params), std::invalid_argument);
  params = {};
  params.smoothing.mu = 0.1f;
  EXPECT_THROW(performer::build_body_mesh(two_bone_skeleton(), params), std::invalid_argument);
}

// --- Marching cubes and smoothing -----------------------------------------------------------------

TEST(MarchingCubes, SphereIsClosedAndOnTheSurface) {
  const float radius = 3.0f;
  const performer::ScalarGrid grid = performer::sample_grid(
      glm::vec3(-4), glm::vec3(4), 0.25f, [&](const glm::vec3& p) { return glm::length(p) - radius; }, 2);
  TriangleMesh mesh = performer::marching_cubes(grid);
  expect_closed_outward(mesh, "sphere");
  for (const glm::vec3& p : mesh.positions) ASSERT_NEAR(glm::length(p), radius, 0.02f);
  const double exact = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  EXPECT_NEAR(signed_volume(mesh), exact, 0.02 * exact);
  // Taubin smoothing keeps the volume (plain Laplacian smoothing would shrink it) and the shape.
  performer::taubin_smooth(mesh.positions, mesh.indices, {});
  EXPECT_NEAR(signed_volume(mesh), exact, 0.02 * exact);
  for (const glm::vec3& p : mesh.positions) ASSERT_NEAR(glm::length(p), radius, 0.05f);
}

TEST(MarchingCubes, RandomFieldsGiveClosedManifolds) {
  // Noise hits every case, ambiguous faces included; the border is kept outside.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int trial = 0; trial < 20; ++trial) {
    performer::ScalarGrid grid;
    grid.nx = grid.ny = grid.nz = 12;
    grid.values.resize(12 * 12 * 12);
    for (int k = 0; k < 12; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          const bool border = i == 0 || j == 0 || k == 0 || i == 11 || j == 11 || k == 11;
          grid.values[grid.index(i, j, k)] = border ? 1.0f : value(rng);
        }
    const TriangleMesh mesh = performer::marching_cubes(grid);
    const EdgeReport r = edge_report(mesh);
    ASSERT_EQ(r.not_in_two, 0u) << "trial " << trial;
    ASSERT_EQ(r.not_opposed, 0u) << "trial " << trial;
    ASSERT_EQ(r.degenerate, 0u) << "trial " << trial;
    // Outward everywhere: each component encloses positive volume, so the total is positive.
    ASSERT_GT(signed_volume(mesh), 0.0) << "trial " << trial;
  }
}

// --- glTF ---------------------------------------------------------------------------------------

// A small skinned mesh with everything the format allows: joints listed before their parents,
// rotations and scales, a joint under a plain node (`above`), and 6 influences (two sets).
SkinnedMesh synthetic_skinned(int influences) {
  SkinnedMesh s;
  const performer::ScalarGrid grid = performer::sample_grid(
      glm::vec3(-1.2f), glm::vec3(1.2f), 0.3f, [](const glm::vec3& p) { return glm::length(p) - 1.0f; }, 1);
  s.mesh = performer::marching_cubes(grid);
  s.mesh.normals.resize(s.mesh.positions.size());
  performer::area_weighted_normals(s.mesh.positions, s.mesh.indices, s.mesh.normals);
  s.joints.resize(4);
  s.joints[0] = {"hand",         2, {0.0f, 0.5f, 0.0f}, glm::angleAxis(0.3f, glm::vec3(1, 0, 0)), glm::vec3(1.0f),
                 glm::mat4(1.0f)};
  s.joints[1] = {"root",
                 -1,
                 {0.1f, -0.2f, 0.3f},
                 glm::quat(1, 0, 0, 0),
                 glm::vec3(1.0f),
                 glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, 0.0f))};
  s.joints[2] = {"arm",
                 1,
                 {0.5f, 0.0f, 0.0f},
                 glm::angleAxis(-0.7f, glm::normalize(glm::vec3(0, 1, 1))),
                 glm::vec3(1.0f, 2.0f, 0.5f),
                 glm::mat4(1.0f)};
  s.joints[3] = {"thumb", 2, {0.0f, 0.0f, 0.25f}, glm::quat(1, 0, 0, 0), glm::vec3(1.0f), glm::mat4(1.0f)};
  std::vector<glm::mat4> local(4), world(4);
  performer::skin_rest_local_transforms(s.joints, local);
  performer::skin_world_transforms(s.joints, local, world);
  s.inverse_bind.resize(4);
  performer::inverse_transforms(world, s.inverse_bind);
  s.influences = influences;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, 3);
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    float sum = 0.0f;
    std::vector<float> w(static_cast<std::size_t>(influences));
    for (float& x : w) sum += (x = weight(rng));
    for (int k = 0; k < influences; ++k) {
      s.joint_indices.push_back(static_cast<std::uint16_t>(pick(rng)));
      s.joint_weights.push_back(w[static_cast<std::size_t>(k)] / sum);
    }
  }
  return s;
}

TEST(GltfSkin, WriteThenReadReproducesEverything) {
  test_support::ScratchDir dir("performer_gltf");
  for (const int influences : {4, 6}) {
    const SkinnedMesh s = synthetic_skinned(influences);
    for (const char* name : {"skin.gltf", "skin.glb"}) {
      const std::string label = std::string(name) + " influences " + std::to_string(influences);
      performer::write_gltf_skinned(dir / name, s);
      const SkinnedMesh r = performer::read_gltf_skinned(dir / name);
      EXPECT_EQ(r.mesh.positions, s.mesh.positions) << label;
      EXPECT_EQ(r.mesh.normals, s.mesh.normals) << label;
      EXPECT_EQ(r.mesh.indices, s.mesh.indices) << label;
      ASSERT_EQ(r.joints.size(), s.joints.size()) << label;
      for (std::size_t j = 0; j < s.joints.size(); ++j) {
        EXPECT_EQ(r.joints[j].name, s.joints[j].name) << label;
        EXPECT_EQ(r.joints[j].parent, s.joints[j].parent) << label;
        EXPECT_EQ(r.joints[j].translation, s.joints[j].translation) << label;
        EXPECT_EQ(r.joints[j].scale, s.joints[j].scale) << label;
        EXPECT_NEAR(std::abs(glm::dot(r.joints[j].rotation, s.joints[j].rotation)), 1.0f, 1e-6f) << label;
        for (int c = 0; c < 4; ++c)
          for (int k = 0; k < 4; ++k) EXPECT_NEAR(r.joints[j].above[c][k], s.joints[j].above[c][k], 1e-6f) << label;
      }
      EXPECT_EQ(r.inverse_bind, s.inverse_bind) << label;
      // Slots come back four per set: 6 influences read as 8, the last two empty.
      ASSERT_EQ(r.influences, influences == 4 ? 4 : 8) << label;
      const auto in = static_cast<std::size_t>(influences), out = static_cast<std::size_t>(r.influences);
      for (std::size_t v = 0; v < s.mesh.positions.size(); ++v)
        for (std::size_t k = 0; k < out; ++k) {
          const float w = k < in ? s.joint_weights[v * in + k] : 0.0f;
          ASSERT_NEAR(r.joint_weights[v * out + k], w, 1e-6f) << label;
          if (k < in) {
            ASSERT_EQ(r.joint_indices[v * out + k], s.joint_indices[v * in + k]) << label;
          }
        }
    }
  }
}

TEST(GltfSkin, LoadedSkinAtRestReproducesPositions) {
  test_support::ScratchDir dir("performer_gltf");
  const SkinnedMesh s = synthetic_skinned(4);
  performer::write_gltf_skinned(dir / "skin.glb", s);
  const SkinnedMesh r = performer::read_gltf_skinned(dir / "skin.glb");
  std::vector<glm::mat4> local(r.joints.size()), world(r.joints.size());
  performer::skin_rest_local_transforms(r.joints, local);
  performer::skin_world_transforms(r.joints, local, world);
  expect_same_mesh(pose(r, world), s.mesh, 1e-5f, "rest");
  // Turning the root turns every vertex rigidly with it.
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.8f, glm::vec3(0, 0, 1));
  local[1] = turn * local[1];
  performer::skin_world_transforms(r.joints, local, world);
  const TriangleMesh posed = pose(r, world);
  const glm::mat4 rigid = r.joints[1].above * turn * glm::inverse(r.joints[1].above);
  for (std::size_t v = 0; v < posed.positions.size(); ++v)
    ASSERT_NEAR(glm::distance(posed.positions[v], glm::vec3(rigid * glm::vec4(s.mesh.positions[v], 1))), 0.0f, 1e-4f);
}

TEST(GltfSkin, WorldTransformsFollowTheHierarchy) {
  const SkinnedMesh s = synthetic_skinned(4);
  std::vector<glm::mat4> local(4), world(4);
  performer::skin_rest_local_transforms(s.joints, local);
  performer::skin_world_transforms(s.joints, local, world);
  const glm::mat4 root = s.joints[1].above * local[1];
  const glm::mat4 arm = root * local[2];
  EXPECT_EQ(world[1], root);
  EXPECT_EQ(world[2], arm);
  EXPECT_EQ(world[0], arm * local[0]);
  EXPECT_EQ(world[3], arm * local[3]);
  auto cyclic = s.joints;
  cyclic[1].parent = 0;  // root under hand under arm under root
  EXPECT_THROW(performer::skin_world_transforms(cyclic, local, world), std::invalid_argument);
  cyclic[1].parent = 9;
  EXPECT_THROW(performer::skin_world_transforms(cyclic, local, world), std::invalid_argument);
}

// Hand-written glTF: the writer only produces one layout, files in the wild use others.
std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t{bytes[i]} << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

struct HandGltf {
  std::vector<std::uint8_t> bytes;
  std::vector<std::string> views, accessors;

  template <typename T>
  int view(const std::vector<T>& data, int stride = 0) {
    while (bytes.size() % 4) bytes.push_back(0);
    const std::size_t offset = bytes.size(), length = data.size() * sizeof(T);
    bytes.resize(offset + length);
    std::memcpy(bytes.data() + offset, data.data(), length);
    views.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" +
                    std::to_string(length) + (stride ? ",\"byteStride\":" + std::to_string(stride) : "") + "}");
    return static_cast<int>(views.size() - 1);
  }
  int accessor(int view, int component, const std::string& type, std::size_t count, const std::string& extra = "") {
    accessors.push_back("{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" + std::to_string(component) +
                        ",\"type\":\"" + type + "\",\"count\":" + std::to_string(count) + extra + "}");
    return static_cast<int>(accessors.size() - 1);
  }
  std::string json(const std::string& meshes, const std::string& skins, const std::string& nodes) const {
    auto list = [](const std::vector<std::string>& items) {
      std::string s = "[";
      for (std::size_t i = 0; i < items.size(); ++i) s += (i ? "," : "") + items[i];
      return s + "]";
    };
    return "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" + std::to_string(bytes.size()) +
           ",\"uri\":\"data:application/octet-stream;base64," + base64(bytes) + "\"}],\"bufferViews\":" + list(views) +
           ",\"accessors\":" + list(accessors) + ",\"meshes\":" + meshes +
           (skins.empty() ? "" : ",\"skins\":" + skins) + ",\"nodes\":" + nodes +
           ",\"scenes\":[{\"nodes\":[0,1]}],\"scene\":0}";
  }
};

constexpr int kUByte = 5121, kUShort = 5123, kFloat = 5126;

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A quad of two triangles bound to two joints, in the layouts real exporters use: unsigned byte
// joints, normalised unsigned byte weights that do not quite add up to 255, unsigned short
// indices, positions and normals interleaved in one strided view, a sparse accessor moving one
// vertex, a joint given as a matrix, and a plain node between the two joints.
struct QuadOptions {
  bool skin = true, joints = true, weights = true, zero_weights = false, overrun = false;
  std::uint8_t joint_value = 1;   // JOINTS_0 of vertex 3
  std::uint16_t index_value = 3;  // last index
};

std::string quad_gltf(const QuadOptions& o) {
  HandGltf g;
  std::vector<float> interleaved;
  const float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& p : quad) interleaved.insert(interleaved.end(), {p[0], p[1], p[2], 0, 0, 1});
  const int vertices = g.view(interleaved, 24);
  const int sparse_index = g.view(std::vector<std::uint8_t>{2, 0, 0, 0});
  const int sparse_value = g.view(std::vector<float>{1.0f, 2.0f, 0.0f});  // vertex 2 moves to (1, 2, 0)
  const int position =
      g.accessor(vertices, kFloat, "VEC3", o.overrun ? 5 : 4,
                 ",\"min\":[0,0,0],\"max\":[1,2,0],\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                     std::to_string(sparse_index) +
                     ",\"componentType\":5121},\"values\":{\"bufferView\":" + std::to_string(sparse_value) + "}}");
  const int normal = g.accessor(vertices, kFloat, "VEC3", 4, ",\"byteOffset\":12");
  const int joints = g.accessor(
      g.view(std::vector<std::uint8_t>{0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, o.joint_value, 0, 0, 0}), kUByte, "VEC4", 4);
  const std::uint8_t z = o.zero_weights ? 0 : 255;
  const int weights =
      g.accessor(g.view(std::vector<std::uint8_t>{z, 0, 0, 0, 100, 50, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0}), kUByte,
                 "VEC4", 4, ",\"normalized\":true");
  const int indices =
      g.accessor(g.view(std::vector<std::uint16_t>{0, 1, 2, 0, 2, o.index_value}), kUShort, "SCALAR", 6);
  std::string attributes = "\"POSITION\":" + std::to_string(position) + ",\"NORMAL\":" + std::to_string(normal);
  if (o.joints) attributes += ",\"JOINTS_0\":" + std::to_string(joints);
  if (o.weights) attributes += ",\"WEIGHTS_0\":" + std::to_string(weights);
  const std::string meshes =
      "[{\"primitives\":[{\"attributes\":{" + attributes + "},\"indices\":" + std::to_string(indices) + "}]}]";
  // Nodes: 0 the mesh, 1 joint "base" given as a matrix (translate 0 1 0, scale 2), 2 a plain node
  // (translate 3 0 0), 3 joint "tip" under it.
  const std::string nodes =
      std::string("[{\"mesh\":0") + (o.skin ? ",\"skin\":0" : "") +
      "},{\"name\":\"base\",\"matrix\":[2,0,0,0,0,2,0,0,0,0,2,0,0,1,0,1],\"children\":[2]},"
      "{\"name\":\"plain\",\"translation\":[3,0,0],\"children\":[3]},{\"name\":\"tip\",\"translation\":[0,1,0]}]";
  return g.json(meshes, o.skin ? "[{\"joints\":[1,3]}]" : "", nodes);
}

TEST(GltfSkin, ReadsTheLayoutsExportersUse) {
  test_support::ScratchDir dir("performer_gltf");
  const fs::path path = dir / "quad.gltf";
  write_text(path, quad_gltf({}));
  const SkinnedMesh r = performer::read_gltf_skinned(path);
  ASSERT_EQ(r.mesh.positions.size(), 4u);
  EXPECT_EQ(r.mesh.positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(r.mesh.positions[2], glm::vec3(1, 2, 0)) << "sparse substitution";
  EXPECT_EQ(r.mesh.normals[3], glm::vec3(0, 0, 1)) << "strided view";
  EXPECT_EQ(r.mesh.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(r.influences, 4);
  EXPECT_EQ(r.joint_indices[4], 0);
  EXPECT_EQ(r.joint_indices[5], 1);
  EXPECT_NEAR(r.joint_weights[4], 100.0f / 150.0f, 1e-6f) << "normalised to sum 1";
  EXPECT_NEAR(r.joint_weights[5], 50.0f / 150.0f, 1e-6f);
  EXPECT_EQ(r.joint_weights[0], 1.0f);
  ASSERT_EQ(r.joints.size(), 2u);
  EXPECT_EQ(r.joints[0].name, "base");
  EXPECT_EQ(r.joints[0].parent, -1);
  EXPECT_NEAR(glm::distance(r.joints[0].translation, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(r.joints[0].scale, glm::vec3(2)), 0.0f, 1e-6f);
  EXPECT_EQ(r.joints[1].name, "tip");
  EXPECT_EQ(r.joints[1].parent, 0);
  EXPECT_EQ(r.joints[1].above, glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 0)));
  EXPECT_EQ(r.inverse_bind, std::vector<glm::mat4>(2, glm::mat4(1.0f))) << "no inverseBindMatrices: identities";
  std::vector<glm::mat4> local(2), world(2);
  performer::skin_rest_local_transforms(r.joints, local);
  performer::skin_world_transforms(r.joints, local, world);
  // tip: base (translate 0 1 0, scale 2) * plain (translate 3 0 0) * tip (translate 0 1 0)
  EXPECT_NEAR(glm::distance(glm::vec3(world[1][3]), glm::vec3(6, 3, 0)), 0.0f, 1e-5f);
}

TEST(GltfSkin, ErrorsNameTheFile) {
  test_support::ScratchDir dir("performer_gltf");
  auto expect_error = [&](const std::string& name, const std::string& text, const std::string& problem) {
    const fs::path path = dir / name;
    write_text(path, text);
    try {
      performer::read_gltf_skinned(path);
      ADD_FAILURE() << name << ": no error";
    } catch (const performer::GltfError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.file(), path.string());
      EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(problem), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  QuadOptions o;
  o.skin = false;
  expect_error("noskin.gltf", quad_gltf(o), "no skin");
  o = {};
  o.joints = false;
  expect_error("nojoints.gltf", quad_gltf(o), "JOINTS_0");
  o = {};
  o.weights = false;
  expect_error("noweights.gltf", quad_gltf(o), "WEIGHTS_0");
  o = {};
  o.joint_value = 2;
  expect_error("badjoint.gltf", quad_gltf(o), "names joint 2 of 2");
  o = {};
  o.index_value = 4;
  expect_error("badindex.gltf", quad_gltf(o), "vertex index 4 of 4");
  o = {};
  o.overrun = true;
  expect_error("overrun.gltf", quad_gltf(o), "overrun");
  o = {};
  o.zero_weights = true;
  expect_error("zeroweights.gltf", quad_gltf(o), "sum to zero");
  expect_error("garbage.gltf", "this is not JSON", "");
  expect_error("empty.glb", "", "");
  expect_error("notgltf.gltf", "{\"asset\":{\"version\":\"2.0\"}}", "no skin");

  // A binary file cut short.
  const SkinnedMesh s = synthetic_skinned(4);
  performer::write_gltf_skinned(dir / "whole.glb", s);
  std::ifstream in(dir / "whole.glb", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expect_error("cut.glb", bytes.substr(0, bytes.size() / 2), "");

  const fs::path missing = dir / "missing.gltf";
  try {
    performer::read_gltf_skinned(missing);
    ADD_FAILURE() << "missing file: no error";
  } catch (const performer::GltfError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos);
  }
  // Writing checks its input and its path.
  SkinnedMesh broken = s;
  broken.joint_indices[0] = 7;
  EXPECT_THROW(performer::write_gltf_skinned(dir / "broken.glb", broken), std::invalid_argument);
  EXPECT_THROW(performer::write_gltf_skinned(dir / "no" / "such" / "dir.glb", s), performer::GltfError);
}

}  // namespace
