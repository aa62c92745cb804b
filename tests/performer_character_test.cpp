// Tests for the whole performer (thesis 3.6): the body and the face merged into one mesh bound to the
// skeleton (character), the integrated deformation of equation 3.20 (character_deform), and the
// `performer pose` command (performer/cli/pose.cpp, compiled into this test).

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shared_assets.h"
#include "support/skeleton_joints.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "../performer/cli/pose.h"
#include "performer/bvh.h"
#include "performer/body_mesh.h"
#include "performer/character.h"
#include "performer/skeleton_skin.h"
#include "performer/character_deform.h"
#include "performer/face_deform.h"
#include "performer/local_transforms.h"
#include "performer/procedural_head.h"
#include "performer/skinning.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"
#include "performer/world_transforms.h"

using performer::Character;
using performer::CharacterFrame;
using performer::FaceModel;
using performer::Skeleton;

namespace {

const performer::VisemeSet& viseme_set() {
  static const performer::VisemeSet set = performer::load_viseme_set(performer::default_viseme_dir() / "visemes.tsv");
  return set;
}

FaceModel head(int rings, int segments) {
  performer::HeadParams p;
  p.rings = rings;
  p.segments = segments;
  return performer::build_procedural_head(viseme_set(), p);
}

using test_support::joint;

// A small figure in centimetres: hips, spine, neck, head, one arm, one leg. Enough for the body to
// have a neck to put the head on and joints that blend.
Skeleton small_skeleton() {
  Skeleton sk;
  sk.joints.push_back(joint("Hips", -1, {0, 0, 0}));
  sk.joints.push_back(joint("Spine", 0, {0, 20, 0}));
  sk.joints.push_back(joint("Neck", 1, {0, 30, 0}));
  sk.joints.push_back(joint("Head", 2, {0, 10, 0}));
  sk.joints.push_back(joint("Head_end", 3, {0, 15, 0}, true));
  sk.joints.push_back(joint("LeftArm", 1, {15, 25, 0}));
  sk.joints.push_back(joint("LeftArm_end", 5, {30, 0, 0}, true));
  sk.joints.push_back(joint("LeftLeg", 0, {8, -5, 0}));
  sk.joints.push_back(joint("LeftLeg_end", 7, {0, -45, 0}, true));
  return sk;
}

performer::CharacterParams small_params(int grid_cells) {
  performer::CharacterParams p;
  p.body.grid_cells = grid_cells;
  p.body.meters_per_unit = 0.01f;
  return p;
}

struct Built {
  Skeleton skeleton;
  FaceModel face;
  Character character;
};

// Coarse: the core tests only need some body and some head.
const Built& small_character() {
  static const Built b = [] {
    Built x{small_skeleton(), head(32, 40), {}};
    x.character = performer::build_character(x.skeleton, x.face, small_params(40));
    return x;
  }();
  return b;
}

// Over three skinning chunks (4096 vertices each), so threading actually splits the work, with the
// head range straddling chunk boundaries.
const Built& medium_character() {
  static const Built b = [] {
    Built x{small_skeleton(), head(90, 112), {}};
    x.character = performer::build_character(x.skeleton, x.face, small_params(96));
    return x;
  }();
  return b;
}

std::vector<glm::mat4> rest_local(const Skeleton& sk) {
  std::vector<glm::mat4> local(sk.joints.size());
  performer::rest_local_transforms(sk, local);
  return local;
}

// Skinning matrices for the rest pose with every movable joint turned a little (deterministically).
std::vector<glm::mat4> bent_matrices(const Skeleton& sk, const Character& c, unsigned seed) {
  std::vector<glm::mat4> local = rest_local(sk), world(sk.joints.size()), out(sk.joints.size());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> angle(-0.6f, 0.6f);
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    if (sk.joints[j].end_site) continue;
    local[j] = glm::rotate(local[j], angle(rng), glm::normalize(glm::vec3(angle(rng), 1.0f, angle(rng))));
  }
  local[0] = glm::translate(glm::mat4(1.0f), glm::vec3(3, 1, -2)) * local[0];
  performer::world_transforms(sk, local, world);
  performer::skinning_matrices(world, c.inverse_bind, out);
  return out;
}

// Some targets on at once, as speech with an expression and a blink would have them.
void set_face_weights(const Character& c, std::vector<float>& weights) {
  std::fill(weights.begin(), weights.end(), 0.0f);
  for (std::size_t t = 0; t < c.targets.size(); ++t) {
    if (c.targets[t].name == "smile") weights[t] = 0.6f;
    if (c.targets[t].name == "blink") weights[t] = 1.0f;
  }
  weights[1] = 0.8f;  // the first non-neutral viseme
}

bool same_bits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// --- The merged mesh ----------------------------------------------------------------------------------

TEST(Character, MergedMeshIsValidBodyThenHead) {
  const Built& b = small_character();
  const Character& c = b.character;
  EXPECT_EQ(performer::character_problem(c), "");
  ASSERT_EQ(c.head_count, b.face.vertex_count());
  EXPECT_EQ(c.head_first + c.head_count, c.vertex_count());
  EXPECT_GT(c.head_first, 100u);
  for (const std::uint32_t i : c.mesh.indices) ASSERT_LT(i, c.vertex_count());
  // The head's triangles are the face's, offset.
  const std::size_t head_indices = b.face.indices.size();
  ASSERT_GE(c.mesh.indices.size(), head_indices);
  for (std::size_t k = 0; k < head_indices; ++k)
    ASSERT_EQ(c.mesh.indices[c.mesh.indices.size() - head_indices + k], b.face.indices[k] + c.head_first);
  // Head placed by head_placement, normals unit.
  for (std::size_t v = 0; v < c.head_count; ++v) {
    const glm::vec3 expected(c.head_placement * glm::vec4(b.face.positions[v], 1.0f));
    ASSERT_LT(glm::distance(c.mesh.positions[c.head_first + v], expected), 1e-4f);
  }
  for (const glm::vec3& n : c.mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  // Head vertices rigid on the head joint; body vertices by SSD, never on end sites.
  EXPECT_EQ(c.head_joint, 3);
  const auto slots = static_cast<std::size_t>(c.influences);
  for (std::size_t v = 0; v < c.vertex_count(); ++v) {
    float sum = 0.0f;
    for (std::size_t k = 0; k < slots; ++k) {
      const float w = c.joint_weights[v * slots + k];
      sum += w;
      if (w > 0.0f) {
        ASSERT_FALSE(b.skeleton.joints[c.joint_indices[v * slots + k]].end_site);
      }
    }
    ASSERT_NEAR(sum, 1.0f, 1e-5f);
    if (v >= c.head_first) {
      ASSERT_EQ(c.joint_indices[v * slots], 3);
      ASSERT_EQ(c.joint_weights[v * slots], 1.0f);
    }
  }
  // Targets cover the head range only and keep the face's order.
  ASSERT_EQ(c.targets.size(), b.face.targets.size());
  for (std::size_t t = 0; t < c.targets.size(); ++t) EXPECT_EQ(c.targets[t].name, b.face.targets[t].name);
}

TEST(Character, SsdHeadBindingIsOffered) {
  const Skeleton sk = small_skeleton();
  auto params = small_params(24);
  params.head = performer::HeadBinding::ssd;
  const FaceModel face = head(24, 24);
  const Character c = performer::build_character(sk, face, params);
  EXPECT_EQ(performer::character_problem(c), "");
  // Some head vertex (the neck stub) is pulled by more than the head joint.
  const auto slots = static_cast<std::size_t>(c.influences);
  bool blended = false;
  for (std::size_t v = c.head_first; v < c.vertex_count(); ++v) blended = blended || c.joint_weights[v * slots] < 1.0f;
  EXPECT_TRUE(blended);
}

TEST(Character, RejectsASkeletonWithoutTheHeadJoint) {
  Skeleton sk = small_skeleton();
  sk.joints[3].name = "Skull";
  sk.joints[4].name = "Skull_end";
  try {
    performer::build_character(sk, head(24, 24), small_params(24));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'Head'"), std::string::npos) << e.what();
  }
}

// --- Equation 3.20 --------------------------------------------------------------------------------

TEST(CharacterDeform, ZeroFaceWeightsEqualSsdAlone) {
  const Built& b = small_character();
  const Character& c = b.character;
  CharacterFrame frame(c);
  frame.matrices = bent_matrices(b.skeleton, c, 7);
  const performer::CharacterDeformJob job = frame.job(c);
  ASSERT_TRUE(job.valid());
  performer::deform_character(job);

  std::vector<glm::vec3> p(c.vertex_count()), n(c.vertex_count());
  performer::SkinningJob skin;
  skin.influences = c.influences;
  skin.matrices = frame.matrices;
  skin.joint_indices = c.joint_indices;
  skin.joint_weights = c.joint_weights;
  skin.in_positions = c.mesh.positions;
  skin.out_positions = p;
  skin.in_normals = c.mesh.normals;
  skin.out_normals = n;
  performer::skin(skin);
  EXPECT_TRUE(same_bits(frame.positions, p));
  EXPECT_TRUE(same_bits(frame.normals, n));
  // And the pose did move things.
  EXPECT_GT(glm::distance(frame.positions[c.head_first], c.mesh.positions[c.head_first]), 1.0f);
}

TEST(CharacterDeform, RestBonesEqualFaceAlone) {
  const Built& b = small_character();
  const Character& c = b.character;
  CharacterFrame frame(c);  // matrices start as the identity: the rest pose
  set_face_weights(c, frame.weights);
  performer::deform_character(frame.job(c));

  // Body untouched (up to the rounding of weights summing to 1).
  for (std::size_t v = 0; v < c.head_first; ++v) {
    ASSERT_LT(glm::distance(frame.positions[v], c.mesh.positions[v]), 1e-4f) << v;
    ASSERT_LT(glm::distance(frame.normals[v], c.mesh.normals[v]), 1e-5f) << v;
  }
  // Head: the face model deformed in its own frame (metres), then placed. This checks the DVs'
  // transformation into the body frame too: positions by the placement, normals by its
  // inverse-transpose and renormalised.
  std::vector<glm::vec3> fp(b.face.vertex_count()), fn(b.face.vertex_count());
  const performer::FaceStreams streams(b.face);
  performer::deform_face({b.face.positions, b.face.normals, streams.positions, streams.normals, frame.weights, fp, fn});
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(c.head_placement)));
  float worst_p = 0.0f, worst_n = 0.0f, moved = 0.0f;
  for (std::size_t v = 0; v < c.head_count; ++v) {
    const glm::vec3 p(c.head_placement * glm::vec4(fp[v], 1.0f));
    const glm::vec3 n = glm::normalize(normal_matrix * fn[v]);
    worst_p = std::max(worst_p, glm::distance(frame.positions[c.head_first + v], p));
    worst_n = std::max(worst_n, glm::distance(frame.normals[c.head_first + v], n));
    moved = std::max(moved, glm::distance(frame.positions[c.head_first + v], c.mesh.positions[c.head_first + v]));
  }
  EXPECT_LT(worst_p, 1e-3f);  // centimetres, over a 23 cm head
  EXPECT_LT(worst_n, 1e-4f);
  EXPECT_GT(moved, 0.3f);  // the face did deform
}

TEST(CharacterDeform, ThreadedEqualsSingleThreadedBitwise) {
  const Built& b = medium_character();
  const Character& c = b.character;
  ASSERT_GT(c.vertex_count(), 3 * 4096u);
  CharacterFrame one(c), many(c);
  one.matrices = many.matrices = bent_matrices(b.skeleton, c, 11);
  set_face_weights(c, one.weights);
  many.weights = one.weights;
  performer::deform_character(one.job(c));
  for (const unsigned threads : {2u, 3u, 8u}) {
    std::fill(many.positions.begin(), many.positions.end(), glm::vec3(0.0f));
    performer::deform_character_parallel(many.job(c), threads);
    EXPECT_TRUE(same_bits(one.positions, many.positions)) << threads << " threads";
    EXPECT_TRUE(same_bits(one.normals, many.normals)) << threads << " threads";
  }
}

TEST(CharacterDeform, RejectsInconsistentJobs) {
  const Character& c = small_character().character;
  CharacterFrame frame(c);
  performer::CharacterDeformJob job = frame.job(c);
  job.head_count += 1;
  EXPECT_FALSE(job.valid());
  EXPECT_THROW(performer::deform_character(job), std::invalid_argument);
  job = frame.job(c);
  job.matrices = job.matrices.first(2);
  EXPECT_FALSE(job.valid());
  EXPECT_THROW(performer::deform_character_parallel(job), std::invalid_argument);
}

// --- CMU motion capture ---------------------------------------------------------------------------

struct CmuCharacter {
  performer::Bvh bvh;
  Character character;
};

const CmuCharacter& cmu_character(const std::string& name) {
  static std::map<std::string, std::unique_ptr<CmuCharacter>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<CmuCharacter>();
    slot->bvh = performer::read_bvh(test_support::bvh_asset(name));
    slot->character = performer::build_character(slot->bvh.skeleton, performer::build_procedural_head(viseme_set()));
  }
  return *slot;
}

TEST(CmuCharacter, HeadFollowsTheHeadJointRigidly) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_01.bvh"));
  const CmuCharacter& cmu = cmu_character("cmu_131_01.bvh");
  const Skeleton& sk = cmu.bvh.skeleton;
  const Character& c = cmu.character;
  ASSERT_EQ(performer::character_problem(c), "");
  ASSERT_EQ(c.head_joint, performer::find_joint(sk, "Head"));
  const int f = cmu.bvh.motion.frames / 2;
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::local_transforms(sk, performer::frame_values(sk, cmu.bvh.motion, f), local);
  performer::world_transforms(sk, local, world);
  CharacterFrame frame(c);
  performer::skinning_matrices(world, c.inverse_bind, frame.matrices);
  performer::deform_character_parallel(frame.job(c));

  // Every head vertex is where the head joint's transform takes it...
  const glm::mat4 head =
      world[static_cast<std::size_t>(c.head_joint)] * c.inverse_bind[static_cast<std::size_t>(c.head_joint)];
  float worst = 0.0f;
  for (std::size_t v = c.head_first; v < c.vertex_count(); ++v)
    worst = std::max(worst, glm::distance(frame.positions[v], glm::vec3(head * glm::vec4(c.mesh.positions[v], 1.0f))));
  EXPECT_LT(worst, 1e-3f);
  // ... so distances within the head are preserved (a rigid motion), though the head has moved.
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::size_t> pick(c.head_first, c.vertex_count() - 1);
  float worst_ratio = 0.0f;
  for (int i = 0; i < 2000; ++i) {
    const std::size_t a = pick(rng), b = pick(rng);
    const float rest = glm::distance(c.mesh.positions[a], c.mesh.positions[b]);
    if (rest < 0.1f) continue;
    const float posed = glm::distance(frame.positions[a], frame.positions[b]);
    worst_ratio = std::max(worst_ratio, std::abs(posed / rest - 1.0f));
  }
  EXPECT_LT(worst_ratio, 1e-4f);
  EXPECT_GT(glm::distance(frame.positions[c.head_first], c.mesh.positions[c.head_first]), 1.0f);
}

// The character's body carries the skeleton-aware weights that binding the body alone gives
// (performer_body_test's SkinHoldsTogetherInMotion checks how that skin holds in motion).
TEST(CmuCharacter, BodyHasTheSkeletonAwareWeights) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_01.bvh"));
  const CmuCharacter& cmu = cmu_character("cmu_131_01.bvh");
  const Character& c = cmu.character;
  const performer::BodyMesh body = performer::build_body_mesh(cmu.bvh.skeleton, performer::CharacterParams{}.body);
  const performer::SkinnedMesh alone = performer::bind_body_to_skeleton(cmu.bvh.skeleton, body);
  ASSERT_EQ(c.head_first, body.mesh.positions.size());
  ASSERT_EQ(c.influences, alone.influences);
  const std::size_t slots = c.head_first * static_cast<std::size_t>(c.influences);
  for (std::size_t i = 0; i < slots; ++i) {
    ASSERT_EQ(c.joint_indices[i], alone.joint_indices[i]) << "slot " << i;
    ASSERT_FLOAT_EQ(c.joint_weights[i], alone.joint_weights[i]) << "slot " << i;
  }
}

std::size_t ply_vertex_count(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  while (std::getline(in, line) && line != "end_header")
    if (line.rfind("element vertex ", 0) == 0) return std::stoul(line.substr(15));
  return 0;
}

TEST(PoseCommand, WritesOneMeshPerFrame) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_02.bvh"));
  const CmuCharacter& cmu = cmu_character("cmu_131_02.bvh");
  test_support::ScratchDir dir("performer_pose");
  performer::cli::PoseCommand command;
  command.bvh = test_support::bvh_asset("cmu_131_02.bvh");
  command.first_frame = 10;
  command.last_frame = 12;
  command.out_dir = dir / "frames";  // created by the command
  // A one-channel track: the smile rising over the three frames.
  performer::WeightTrack track;
  track.fps = 1.0 / cmu.bvh.motion.frame_time;
  track.channels = {"smile", "no_such_target"};
  track.times = {0.0, cmu.bvh.motion.frame_time, 2 * cmu.bvh.motion.frame_time};
  track.values = {0.0f, 0.0f, 0.5f, 0.0f, 1.0f, 0.0f};
  command.weights = &track;
  performer::cli::run_pose(command, stderr);
  for (int f = 10; f <= 12; ++f) {
    const auto file = command.out_dir / ("frame_000" + std::to_string(f) + ".ply");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    EXPECT_EQ(ply_vertex_count(file), cmu.character.vertex_count()) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(command.out_dir / "frame_00013.ply"));

  command.format = "obj";
  command.out_dir = dir / "obj";
  command.first_frame = command.last_frame = 0;
  command.weights = nullptr;
  performer::cli::run_pose(command, stderr);
  EXPECT_TRUE(std::filesystem::exists(command.out_dir / "frame_00000.obj"));
}

TEST(PoseCommand, ErrorsNameTheProblem) {
  test_support::ScratchDir dir("performer_pose");
  performer::cli::PoseCommand command;
  command.bvh = test_support::bvh_asset("cmu_131_02.bvh");
  command.out_dir = dir / "frames";
  command.format = "png";
  try {
    performer::cli::run_pose(command, stderr);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("png"), std::string::npos) << e.what();
  }
  REQUIRE_SHARED_FILE(command.bvh);
  command.format = "ply";
  command.first_frame = 5;
  command.last_frame = 1000000;
  try {
    performer::cli::run_pose(command, stderr);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1000000"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(command.out_dir));
}

}  // namespace
