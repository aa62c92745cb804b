// glTF avatars as the performer (performer/avatar.h, performer/gltf_avatar.h): the skin and the face
// read from one file, the avatar made a Character (four strongest influences, the face range), its
// joints following a BVH clip's by name, and, on the CMU clips, an avatar dressed as a foreign rig
// (support/avatar_fixture.h: other names, turned joint frames, an extra joint) moving exactly as the
// generated performer it was made from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "performer/avatar.h"
#include "performer/bvh.h"
#include "performer/character_deform.h"
#include "performer/face_deform.h"
#include "performer/gltf_avatar.h"
#include "performer/gltf_face.h"
#include "performer/gltf_skin.h"
#include "performer/local_transforms.h"
#include "performer/skinning.h"
#include "performer/world_transforms.h"
#include "support/avatar_fixture.h"
#include "support/scratch_dir.h"
#include "support/shared_assets.h"
#include "support/skeleton_joints.h"

namespace fs = std::filesystem;
using performer::Character;
using performer::SkinnedMesh;

namespace {

const performer::VisemeSet& viseme_set() {
  static const performer::VisemeSet set = performer::load_viseme_set(performer::default_viseme_dir() / "visemes.tsv");
  return set;
}

// A strip of four quads up the y axis, bound to a chain Hips -> Spine -> Head (1 unit apart), each
// vertex to its nearest joint and, with 8 slots, to the others a little.
SkinnedMesh small_skin(int influences) {
  SkinnedMesh s;
  for (int row = 0; row <= 4; ++row)
    for (int col = 0; col < 2; ++col) {
      s.mesh.positions.emplace_back(0.5f * static_cast<float>(col), 0.5f * static_cast<float>(row), 0.0f);
      s.mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  for (std::uint32_t row = 0; row < 4; ++row) {
    const std::uint32_t a = row * 2, b = a + 1, c = a + 2, d = a + 3;
    s.mesh.indices.insert(s.mesh.indices.end(), {a, b, d, a, d, c});
  }
  const char* names[] = {"Hips", "Spine", "Head"};
  for (int j = 0; j < 3; ++j) {
    performer::SkinJoint joint;
    joint.name = names[j];
    joint.parent = j - 1;
    joint.translation = glm::vec3(0.0f, j == 0 ? 0.0f : 1.0f, 0.0f);
    s.joints.push_back(joint);
    s.inverse_bind.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -static_cast<float>(j), 0.0f)));
  }
  s.influences = influences;
  for (const glm::vec3& p : s.mesh.positions) {
    const int nearest = std::clamp(static_cast<int>(std::lround(p.y)), 0, 2);
    for (int k = 0; k < influences; ++k) {
      // Slot 0 the nearest joint; the others spread thinly over all three.
      s.joint_indices.push_back(static_cast<std::uint16_t>(k == 0 ? nearest : k % 3));
      s.joint_weights.push_back(k == 0 ? 0.6f : 0.4f / static_cast<float>(influences - 1));
    }
  }
  return s;
}

// Targets named after two of the thesis' visemes (first and last in the set), moving the top row.
std::vector<performer::MorphTarget> small_targets(std::size_t vertices) {
  std::vector<performer::MorphTarget> targets;
  for (const std::string& name : {viseme_set().visemes.front().name, viseme_set().visemes.back().name}) {
    performer::MorphTarget t{name, std::vector<glm::vec3>(vertices, glm::vec3(0.0f)),
                             std::vector<glm::vec3>(vertices, glm::vec3(0.0f))};
    for (std::size_t v = vertices - 2; v < vertices; ++v) {
      t.position_deltas[v] = glm::vec3(0.0f, 0.0f, 0.1f * static_cast<float>(targets.size() + 1));
      t.normal_deltas[v] = glm::vec3(0.0f, -0.1f, 0.0f);
    }
    targets.push_back(t);
  }
  return targets;
}

TEST(Avatar, CharacterKeepsTheFourStrongestInfluencesAndTheMovedRange) {
  const SkinnedMesh skin = small_skin(8);
  performer::FaceModel face{skin.mesh.positions, skin.mesh.normals, skin.mesh.indices, small_targets(10)};
  const Character c = performer::avatar_character(skin, face);
  EXPECT_EQ(performer::character_problem(c), "");
  ASSERT_EQ(c.influences, 4);
  for (std::size_t v = 0; v < c.vertex_count(); ++v) {
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) sum += c.joint_weights[v * 4 + static_cast<std::size_t>(k)];
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
    // 0.6 then three of the seven 0.4/7 slots, renormalised; the strongest stays first.
    EXPECT_NEAR(c.joint_weights[v * 4], 0.6f / (0.6f + 3.0f * 0.4f / 7.0f), 1e-6f);
    EXPECT_EQ(c.joint_indices[v * 4], skin.joint_indices[v * 8]);
  }
  // The face range: from the first vertex a target moves (the top row) to the end.
  EXPECT_EQ(c.head_first, 8u);
  EXPECT_EQ(c.head_count, 2u);
  ASSERT_EQ(c.targets.size(), 2u);
  EXPECT_EQ(c.targets[1].position_deltas[0], glm::vec3(0.0f, 0.0f, 0.2f));
  EXPECT_EQ(c.head_joint, -1);
  // No targets: no face range.
  face.targets.clear();
  const Character still = performer::avatar_character(skin, face);
  EXPECT_EQ(still.head_count, 0u);
  face.positions.pop_back();
  EXPECT_THROW(performer::avatar_character(skin, face), std::invalid_argument);
}

TEST(GltfAvatar, SkinAndFaceComeFromOneFile) {
  const test_support::ScratchDir dir("gltf_avatar");
  const SkinnedMesh skin = small_skin(4);
  const std::vector<performer::MorphTarget> targets = small_targets(10);
  for (const char* name : {"avatar.glb", "avatar.gltf"}) {
    performer::write_gltf_skinned(dir / name, skin, targets);
    const performer::GltfAvatar avatar = performer::load_gltf_avatar(dir / name, viseme_set());
    ASSERT_TRUE(avatar.skinned);
    EXPECT_EQ(avatar.skin.mesh.positions, skin.mesh.positions);
    EXPECT_EQ(avatar.skin.joint_weights, skin.joint_weights);
    EXPECT_EQ(avatar.face.positions, skin.mesh.positions);
    EXPECT_EQ(avatar.face.indices, skin.mesh.indices);
    for (const performer::MorphTarget& t : targets) {
      const performer::MorphTarget* read = avatar.face.target(t.name);
      ASSERT_NE(read, nullptr) << t.name;
      EXPECT_EQ(read->position_deltas, t.position_deltas);
      EXPECT_EQ(read->normal_deltas, t.normal_deltas);
    }
  }
  // A skin without morph targets: a face with no targets, the skin all the same.
  performer::write_gltf_skinned(dir / "plain.glb", skin);
  const performer::GltfAvatar plain = performer::load_gltf_avatar(dir / "plain.glb", viseme_set());
  EXPECT_TRUE(plain.skinned);
  EXPECT_TRUE(plain.face.targets.empty());
  EXPECT_EQ(plain.face.vertex_count(), 10u);
  // A face without a skin comes back as the face alone.
  performer::write_gltf_face(dir / "face.glb", {skin.mesh.positions, skin.mesh.normals, skin.mesh.indices, targets});
  const performer::GltfAvatar face = performer::load_gltf_avatar(dir / "face.glb", viseme_set());
  EXPECT_FALSE(face.skinned);
  EXPECT_NE(face.face.target(targets[0].name), nullptr);
  // Neither: refused, naming the file and what is missing.
  performer::write_gltf_face(dir / "bare.glb", {skin.mesh.positions, skin.mesh.normals, skin.mesh.indices, {}});
  try {
    performer::load_gltf_avatar(dir / "bare.glb", viseme_set());
    ADD_FAILURE() << "a mesh with neither skin nor morph targets was accepted";
  } catch (const performer::GltfError& e) {
    EXPECT_NE(std::string(e.what()).find("bare.glb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no skinned mesh and no morph targets"), std::string::npos) << e.what();
  }
}

TEST(Retarget, MatchesByNameIgnoringCaseAndNamespace) {
  using test_support::joint;
  performer::Skeleton sk;
  sk.joints = {joint("Hips", -1, {0, 0, 0}), joint("Spine", 0, {0, 2, 0}), joint("Head", 1, {0, 2, 0}),
               joint("Head_end", 2, {0, 1, 0}, true)};
  SkinnedMesh avatar = small_skin(4);
  avatar.joints[0].name = "mixamorig:hips";
  avatar.joints[1].name = "SPINE";
  avatar.joints[2].name = "Ponytail";
  const performer::AvatarRetarget r = performer::retarget_by_name(avatar, sk);
  EXPECT_EQ(r.skeleton_joint, (std::vector<int>{0, 1, -1}));
  EXPECT_EQ(r.unmatched, (std::vector<std::string>{"Ponytail"}));
  EXPECT_EQ(r.root, 0);
  EXPECT_EQ(r.anchor, (std::vector<bool>{true, false, false}));
  EXPECT_FLOAT_EQ(r.scale, 0.5f);  // hips to spine: 1 avatar unit, 2 clip units

  // The clip turns the spine a quarter turn about z and moves the hips: the avatar's spine turns so
  // about its own place, its unmatched child turns with it, the hips move half as far.
  std::vector<glm::mat4> world(4);
  world[0] = glm::translate(glm::mat4(1.0f), glm::vec3(4.0f, 0.0f, 0.0f));
  world[1] = world[0] * glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0)) *
             glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 0, 1));
  world[2] = world[1] * glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0));
  world[3] = world[2] * glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
  std::vector<glm::mat4> posed(3);
  performer::retarget_pose(r, world, posed);
  auto at = [](const glm::mat4& m) { return glm::vec3(m[3]); };
  EXPECT_LT(glm::distance(at(posed[0]), glm::vec3(2, 0, 0)), 1e-6f);
  EXPECT_LT(glm::distance(at(posed[1]), glm::vec3(2, 1, 0)), 1e-6f);
  EXPECT_LT(glm::distance(at(posed[2]), glm::vec3(1, 1, 0)), 1e-6f);  // the head, swung to -x
  std::vector<glm::mat4> too_few(3);
  EXPECT_THROW(performer::retarget_pose(r, std::span(world).first(1), posed), std::invalid_argument);
}

// --- The CMU clips ----------------------------------------------------------------------------------

// Row f of the clip for the skeleton scaled to metres: position channels scaled too.
std::vector<float> row_in_metres(const performer::Bvh& bvh, int f) {
  const auto row = performer::frame_values(bvh.skeleton, bvh.motion, f);
  std::vector<float> out(row.begin(), row.end());
  for (const performer::Joint& j : bvh.skeleton.joints)
    for (std::size_t k = 0; k < j.channels.size(); ++k)
      if (!performer::is_rotation(j.channels[k]))
        out[static_cast<std::size_t>(j.channel_offset) + k] *= performer::BodyMeshParams{}.meters_per_unit;
  return out;
}

TEST(CmuAvatar, ForeignRigMovesAsTheGeneratedPerformer) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_02.bvh"));
  const performer::Bvh bvh = performer::read_bvh(test_support::bvh_asset("cmu_131_02.bvh"));
  const test_support::ScratchDir dir("cmu_avatar");
  const test_support::TestAvatar made = test_support::write_test_avatar(bvh.skeleton, dir / "avatar.glb");
  EXPECT_GT(made.rebound_vertices, 10u);
  const performer::GltfAvatar avatar = performer::load_gltf_avatar(dir / "avatar.glb", viseme_set());
  ASSERT_TRUE(avatar.skinned);
  const Character c = performer::avatar_character(avatar.skin, avatar.face);
  const performer::AvatarRetarget r = performer::retarget_by_name(avatar.skin, bvh.skeleton);
  EXPECT_EQ(r.unmatched, (std::vector<std::string>{"Prop"}));
  EXPECT_NEAR(r.scale / performer::BodyMeshParams{}.meters_per_unit, 1.0f, 1e-5f);
  const Character& g = made.generated;
  ASSERT_EQ(c.vertex_count(), g.vertex_count());
  ASSERT_EQ(c.targets.size(), g.targets.size());
  EXPECT_GE(c.head_first, g.head_first);  // the face range starts where the head's targets first move

  const performer::Skeleton& sk = bvh.skeleton;
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size()), posed(c.inverse_bind.size());
  performer::CharacterFrame avatar_frame(c), generated_frame(g);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : g.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  float worst_position = 0.0f, worst_normal = 0.0f;
  for (int k = 0; k < 5; ++k) {
    const int f = k * (bvh.motion.frames - 1) / 4;
    // Both faces: a viseme and an expression (the same targets, in the same order).
    for (std::size_t t = 0; t < c.targets.size(); ++t)
      avatar_frame.weights[t] = generated_frame.weights[t] =
          t == static_cast<std::size_t>(k) || t == c.targets.size() - 2 ? 0.7f : 0.0f;
    performer::local_transforms(sk, performer::frame_values(sk, bvh.motion, f), local);
    performer::world_transforms(sk, local, world);
    performer::retarget_pose(r, world, posed);
    performer::skinning_matrices(posed, c.inverse_bind, avatar_frame.matrices);
    performer::deform_character_parallel(avatar_frame.job(c));
    performer::local_transforms(made.skeleton_in_metres, row_in_metres(bvh, f), local);
    performer::world_transforms(made.skeleton_in_metres, local, world);
    performer::skinning_matrices(world, g.inverse_bind, generated_frame.matrices);
    performer::deform_character_parallel(generated_frame.job(g));
    for (std::size_t v = 0; v < c.vertex_count(); ++v) {
      worst_position =
          std::max(worst_position, glm::distance(avatar_frame.positions[v], generated_frame.positions[v]) / size);
      worst_normal = std::max(worst_normal, glm::distance(avatar_frame.normals[v], generated_frame.normals[v]));
    }
  }
  std::printf("foreign rig against the generated performer: positions within %.2g of the size, normals within %.2g\n",
              worst_position, worst_normal);
  EXPECT_LT(worst_position, 1e-5f);
  EXPECT_LT(worst_normal, 1e-4f);
}

}  // namespace
