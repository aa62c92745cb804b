// Tests for skeletal subspace deformation (thesis 3.5.4): bone weights by equation 3.18, vertex
// deformation by 3.17 and normals by 3.19 (inverse-transpose form), serial and threaded.

#include <gtest/gtest.h>

#include "support/shared_assets.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "performer/bvh.h"
#include "performer/local_transforms.h"
#include "performer/skeleton.h"
#include "performer/skinning.h"
#include "performer/ssd_weights.h"
#include "performer/world_transforms.h"

namespace fs = std::filesystem;
using performer::Channel;
using performer::Skeleton;

namespace {

using test_support::bvh_asset;
#define REQUIRE_BVH_ASSET(path) REQUIRE_SHARED_FILE(path)

// An "arm": three joints 4 units apart along +y, each with full ZYX rotation, the root also movable.
Skeleton arm_skeleton() {
  Skeleton sk;
  const std::vector<Channel> zyx{Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  performer::Joint root;
  root.name = "root";
  root.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                   Channel::Zrotation, Channel::Yrotation, Channel::Xrotation};
  sk.joints.push_back(root);
  for (int i = 1; i <= 2; ++i) {
    performer::Joint j;
    j.name = "j" + std::to_string(i);
    j.parent = i - 1;
    j.offset = {0, 4, 0};
    j.channels = zyx;
    j.channel_offset = 6 + 3 * (i - 1);
    sk.joints.push_back(j);
  }
  performer::Joint tip;
  tip.name = "j2_end";
  tip.parent = 2;
  tip.offset = {0, 4, 0};
  tip.end_site = true;
  tip.channel_offset = 12;
  sk.joints.push_back(tip);
  return sk;
}

// A closed-off tube of radius 1 around the arm, y from -1 to 13, with outward normals; ~18k
// vertices so the threaded paths really split.
struct Mesh {
  std::vector<glm::vec3> positions, normals;
};
Mesh tube() {
  Mesh m;
  const int segments = 64;
  for (int ring = 0; ring <= 280; ++ring) {
    const float y = -1.0f + 0.05f * ring;
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * std::numbers::pi_v<float> * s / segments;
      m.positions.emplace_back(std::cos(a), y, std::sin(a));
      m.normals.emplace_back(std::cos(a), 0.0f, std::sin(a));
    }
  }
  return m;
}

std::vector<glm::mat4> world_of(const Skeleton& sk, const std::vector<float>& row,
                                const glm::mat4& model = glm::mat4(1.0f)) {
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::local_transforms(sk, row, local);
  for (std::size_t j = 0; j < sk.joints.size(); ++j)
    if (sk.joints[j].parent < 0) local[j] = model * local[j];  // place the figure: premultiply roots
  performer::world_transforms(sk, local, world);
  return world;
}

std::vector<glm::vec3> joint_positions(const std::vector<glm::mat4>& world) {
  std::vector<glm::vec3> p;
  for (const auto& m : world) p.emplace_back(m[3]);
  return p;
}

// Everything a skinned mesh needs: bind data plus output buffers.
struct Skinned {
  int influences;
  std::vector<std::uint16_t> joints;
  std::vector<float> weights;
  std::vector<glm::mat4> inverse_rest;
  std::vector<glm::vec3> positions, normals;

  Skinned(const Skeleton& sk, const Mesh& mesh, performer::SsdWeightParams params = {})
      : influences(params.max_influences) {
    const auto rest = world_of(sk, std::vector<float>(static_cast<std::size_t>(performer::channel_count(sk)), 0.0f));
    inverse_rest.resize(rest.size());
    performer::inverse_transforms(rest, inverse_rest);
    joints.resize(mesh.positions.size() * static_cast<std::size_t>(influences));
    weights.resize(joints.size());
    performer::ssd_weights(mesh.positions, joint_positions(rest), params, joints, weights);
    positions.resize(mesh.positions.size());
    normals.resize(mesh.normals.size());
  }

  void deform(const Mesh& mesh, const std::vector<glm::mat4>& world, unsigned threads = 0) {
    std::vector<glm::mat4> skinning(world.size());
    performer::skinning_matrices(world, inverse_rest, skinning);
    performer::SkinningJob job;
    job.influences = influences;
    job.matrices = skinning;
    job.joint_indices = joints;
    job.joint_weights = weights;
    job.in_positions = mesh.positions;
    job.out_positions = positions;
    job.in_normals = mesh.normals;
    job.out_normals = normals;
    performer::skin_parallel(job, threads);
  }
};

// --- Weights (3.18) -----------------------------------------------------------------------------

TEST(SsdWeights, NormalisedSparseAndNearestFirst) {
  const Skeleton sk = arm_skeleton();
  const Mesh mesh = tube();
  const auto rest = joint_positions(world_of(sk, std::vector<float>(12, 0.0f)));
  for (const int max_influences : {1, 2, 3, 4, 8}) {
    for (const float n : {0.0f, 1.0f, 2.0f, 8.0f}) {
      performer::SsdWeightParams p;
      p.max_influences = max_influences;
      p.n = n;
      const std::size_t slots = static_cast<std::size_t>(max_influences);
      std::vector<std::uint16_t> idx(mesh.positions.size() * slots);
      std::vector<float> w(idx.size());
      performer::ssd_weights(mesh.positions, rest, p, idx, w);
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        float sum = 0.0f;
        int nonzero = 0;
        float farthest_kept = 0.0f;
        for (std::size_t i = 0; i < slots; ++i) {
          const float wi = w[v * slots + i];
          ASSERT_GE(wi, 0.0f);
          ASSERT_LT(idx[v * slots + i], rest.size());
          if (i > 0) {
            ASSERT_LE(wi, w[v * slots + i - 1]) << "strongest first";
          }
          sum += wi;
          if (wi > 0.0f) {
            ++nonzero;
            farthest_kept = std::max(farthest_kept, glm::distance(mesh.positions[v], rest[idx[v * slots + i]]));
          }
        }
        ASSERT_NEAR(sum, 1.0f, 1e-5f) << "vertex " << v;
        ASSERT_LE(nonzero, max_influences);
        ASSERT_EQ(nonzero, std::min<int>(max_influences, static_cast<int>(rest.size())));
        // No joint left out is nearer than one kept (n > 0: nearer means stronger).
        if (n > 0.0f)
          for (std::size_t b = 0; b < rest.size(); ++b) {
            const bool kept =
                std::find(idx.begin() + static_cast<long>(v * slots), idx.begin() + static_cast<long>((v + 1) * slots),
                          b) != idx.begin() + static_cast<long>((v + 1) * slots);
            if (!kept) {
              ASSERT_GE(glm::distance(mesh.positions[v], rest[b]) + 1e-5f, farthest_kept);
            }
          }
      }
    }
  }
}

TEST(SsdWeights, Equation318ByHand) {
  // Vertex at distance 1 from joint 0 and 3 from joint 1 (and far from joint 2): with n = 2 and two
  // influences, w ~ 1/1 and 1/9, normalised: 0.9 and 0.1.
  const std::vector<glm::vec3> joints{{0, 0, 0}, {4, 0, 0}, {100, 0, 0}};
  const std::vector<glm::vec3> vertex{{1, 0, 0}};
  std::vector<std::uint16_t> idx(2);
  std::vector<float> w(2);
  performer::SsdWeightParams p;
  p.max_influences = 2;
  p.n = 2.0f;
  for (const float k : {1.0f, 7.5f}) {  // k scales all weights alike and cancels
    p.k = k;
    performer::ssd_weights(vertex, joints, p, idx, w);
    EXPECT_EQ(idx[0], 0);
    EXPECT_EQ(idx[1], 1);
    EXPECT_NEAR(w[0], 0.9f, 1e-6f);
    EXPECT_NEAR(w[1], 0.1f, 1e-6f);
  }
  p.n = 1.0f;  // 1/1 and 1/3: 0.75 and 0.25
  performer::ssd_weights(vertex, joints, p, idx, w);
  EXPECT_NEAR(w[0], 0.75f, 1e-6f);
  EXPECT_NEAR(w[1], 0.25f, 1e-6f);
  // A vertex on a joint belongs to it.
  const std::vector<glm::vec3> on_joint{{4, 0, 0}};
  performer::ssd_weights(on_joint, joints, p, idx, w);
  EXPECT_EQ(idx[0], 1);
  EXPECT_GT(w[0], 0.999f);
  // Bad parameters.
  p.max_influences = 0;
  EXPECT_THROW(performer::ssd_weights(vertex, joints, p, idx, w), std::invalid_argument);
  p.max_influences = 2;
  p.n = -1.0f;
  EXPECT_THROW(performer::ssd_weights(vertex, joints, p, idx, w), std::invalid_argument);
}

TEST(SsdWeights, ThreadCountDoesNotChangeTheResult) {
  const Skeleton sk = arm_skeleton();
  const Mesh mesh = tube();
  const auto rest = joint_positions(world_of(sk, std::vector<float>(12, 0.0f)));
  std::vector<std::uint16_t> i1(mesh.positions.size() * 4), i4(i1.size());
  std::vector<float> w1(i1.size()), w4(i1.size());
  performer::ssd_weights(mesh.positions, rest, {}, i1, w1, 1);
  performer::ssd_weights(mesh.positions, rest, {}, i4, w4, 4);
  EXPECT_EQ(i1, i4);
  EXPECT_EQ(w1, w4);
}

// --- Deformation (3.17, 3.19) -------------------------------------------------------------------

TEST(Skinning, RestPoseLeavesTheMeshUnchanged) {
  const Skeleton sk = arm_skeleton();
  const Mesh mesh = tube();
  Skinned s(sk, mesh);
  s.deform(mesh, world_of(sk, std::vector<float>(12, 0.0f)));
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    ASSERT_LT(glm::distance(s.positions[v], mesh.positions[v]), 1e-5f) << v;
    ASSERT_LT(glm::distance(s.normals[v], mesh.normals[v]), 1e-5f) << v;
  }
}

glm::mat4 some_rigid_motion() {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, -2.0f, 7.5f));
  m = glm::rotate(m, 1.1f, glm::normalize(glm::vec3(0.3f, 1.0f, -0.4f)));
  return m;
}

TEST(Skinning, RigidMotionOfTheRootMovesTheMeshRigidly) {
  const Skeleton sk = arm_skeleton();
  const Mesh mesh = tube();
  Skinned s(sk, mesh);
  const glm::mat4 m = some_rigid_motion();
  const glm::mat3 r(m);

  // Rest pose moved as a whole: every vertex is exactly M v.
  s.deform(mesh, world_of(sk, std::vector<float>(12, 0.0f), m));
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    ASSERT_LT(glm::distance(s.positions[v], glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f))), 1e-4f) << v;
    ASSERT_LT(glm::distance(s.normals[v], r * mesh.normals[v]), 1e-5f) << v;
  }

  // A bent arm, then the same bent arm moved: the second is the first moved rigidly, normals unit.
  const std::vector<float> bent{0.5f, 1.0f, -0.3f, 10, 20, 5, 60, -15, 30, -80, 25, 10};
  s.deform(mesh, world_of(sk, bent));
  const auto posed = s.positions;
  const auto posed_normals = s.normals;
  s.deform(mesh, world_of(sk, bent, m));
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    ASSERT_LT(glm::distance(s.positions[v], glm::vec3(m * glm::vec4(posed[v], 1.0f))), 1e-4f) << v;
    ASSERT_LT(glm::distance(s.normals[v], r * posed_normals[v]), 1e-5f) << v;
    ASSERT_NEAR(glm::length(s.normals[v]), 1.0f, 1e-5f) << v;
  }
}

TEST(Skinning, Equation317And319ByHand) {
  // Two bones at the origin; bone 1 turned 90 degrees about z. A vertex half on each.
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), std::numbers::pi_v<float> / 2, glm::vec3(0, 0, 1));
  const std::vector<glm::mat4> matrices{glm::mat4(1.0f), turn};
  const std::vector<std::uint16_t> idx{0, 1};
  const std::vector<float> w{0.5f, 0.5f};
  const std::vector<glm::vec3> in{{1, 0, 0}};
  const glm::vec3 n0 = glm::normalize(glm::vec3(1, 2, 0.5f));
  const std::vector<glm::vec3> in_n{n0};
  std::vector<glm::vec3> out(1), out_n(1);
  performer::SkinningJob job;
  job.influences = 2;
  job.matrices = matrices;
  job.joint_indices = idx;
  job.joint_weights = w;
  job.in_positions = in;
  job.out_positions = out;
  job.in_normals = in_n;
  job.out_normals = out_n;
  performer::skin(job);
  // (0.5 I + 0.5 Rz90) (1, 0, 0) = (0.5, 0.5, 0)
  EXPECT_NEAR(out[0].x, 0.5f, 1e-6f);
  EXPECT_NEAR(out[0].y, 0.5f, 1e-6f);
  EXPECT_NEAR(out[0].z, 0.0f, 1e-6f);
  // Normal: inverse-transpose of the blended linear part (not itself a rotation), renormalised.
  const glm::mat3 blended = 0.5f * glm::mat3(1.0f) + 0.5f * glm::mat3(turn);
  const glm::vec3 expected = glm::normalize(glm::inverseTranspose(blended) * n0);
  EXPECT_LT(glm::distance(out_n[0], expected), 1e-6f);

  // Skinning in place gives the same.
  std::vector<glm::vec3> inplace = in, inplace_n = in_n;
  job.in_positions = inplace;
  job.out_positions = inplace;
  job.in_normals = inplace_n;
  job.out_normals = inplace_n;
  performer::skin(job);
  EXPECT_EQ(inplace[0], out[0]);
  EXPECT_EQ(inplace_n[0], out_n[0]);

  // Inconsistent jobs are refused.
  const std::vector<std::uint16_t> bad_idx{0, 2};
  job.joint_indices = bad_idx;
  EXPECT_FALSE(job.valid());
  EXPECT_THROW(performer::skin(job), std::invalid_argument);
}

TEST(Skinning, ThreadedEqualsSerial) {
  const Skeleton sk = arm_skeleton();
  const Mesh mesh = tube();
  Skinned s(sk, mesh);
  const std::vector<float> bent{0.5f, 1.0f, -0.3f, 10, 20, 5, 60, -15, 30, -80, 25, 10};
  s.deform(mesh, world_of(sk, bent), 1);
  const auto serial = s.positions;
  const auto serial_n = s.normals;
  for (const unsigned threads : {2u, 3u, 8u}) {
    s.deform(mesh, world_of(sk, bent), threads);
    EXPECT_EQ(s.positions, serial) << threads;
    EXPECT_EQ(s.normals, serial_n) << threads;
  }
}

// The CMU skeleton with a point cloud around its bones: rest reproduces it, a mocap frame moved
// rigidly moves the deformed cloud rigidly.
TEST(Skinning, CmuSkeletonRestAndRigidMotion) {
  const fs::path path = bvh_asset("cmu_131_02.bvh");
  REQUIRE_BVH_ASSET(path);
  const performer::Bvh bvh = performer::read_bvh(path);
  const Skeleton& sk = bvh.skeleton;
  const auto rest = world_of(sk, std::vector<float>(96, 0.0f));
  Mesh cloud;
  std::mt19937 rng(131);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    const glm::vec3 a(rest[static_cast<std::size_t>(sk.joints[j].parent)][3]), b(rest[j][3]);
    for (int i = 0; i < 300; ++i) {
      const float t = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
      cloud.positions.push_back(glm::mix(a, b, t) + 0.8f * glm::vec3(g(rng), g(rng), g(rng)));
      cloud.normals.push_back(glm::normalize(glm::vec3(g(rng), g(rng), g(rng)) + glm::vec3(1e-3f)));
    }
  }
  Skinned s(sk, cloud);
  s.deform(cloud, rest);
  for (std::size_t v = 0; v < cloud.positions.size(); ++v) {
    ASSERT_LT(glm::distance(s.positions[v], cloud.positions[v]), 1e-5f) << v;
    ASSERT_LT(glm::distance(s.normals[v], cloud.normals[v]), 1e-5f) << v;
  }

  const auto row = performer::frame_values(sk, bvh.motion, 600);
  const std::vector<float> frame(row.begin(), row.end());
  s.deform(cloud, world_of(sk, frame));
  const auto posed = s.positions;
  const auto posed_n = s.normals;
  const glm::mat4 m = some_rigid_motion();
  s.deform(cloud, world_of(sk, frame, m));
  for (std::size_t v = 0; v < cloud.positions.size(); ++v) {
    ASSERT_LT(glm::distance(s.positions[v], glm::vec3(m * glm::vec4(posed[v], 1.0f))), 1e-4f) << v;
    ASSERT_LT(glm::distance(s.normals[v], glm::mat3(m) * posed_n[v]), 1e-4f) << v;
    ASSERT_NEAR(glm::length(s.normals[v]), 1.0f, 1e-5f) << v;
  }
}

}  // namespace
