#pragma once
// A glTF avatar made by our own code for the tests, never a downloaded model: the generated performer
// (the body grown around a BVH skeleton, the procedural head) in metres, exported with
// character_avatar, then dressed as a rig from elsewhere would be:
//   - joint names in a "mixamorig:" namespace and in upper case (matched by name regardless);
//   - every joint's frame turned at rest, as artists' rigs have them: local rotations, translations
//     and inverse binds changed together, so the bind pose is the very same mesh;
//   - one more joint the clip does not have ("Prop", under the left elbow), holding the forearm's
//     share of every other vertex the elbow joint moves: unmatched, it must move as its parent does.
// Retargeted onto the clip, such an avatar must move exactly as the generated performer does.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "performer/avatar.h"
#include "performer/body_mesh.h"
#include "performer/character.h"
#include "performer/gltf_skin.h"
#include "performer/procedural_head.h"
#include "performer/skinning.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"

namespace test_support {

struct TestAvatar {
  performer::Character generated;          // the performer it was made from, in metres
  performer::Skeleton skeleton_in_metres;  // the clip's skeleton scaled to metres: it poses `generated`
  std::size_t rebound_vertices = 0;        // vertices that hand their elbow joint weight to "Prop"
};

// Joint j's frame at rest, turned by an arbitrary but fixed rotation.
inline glm::quat test_rest_turn(std::size_t j) {
  const float a = static_cast<float>(j);
  return glm::angleAxis(0.3f + 0.7f * a, glm::normalize(glm::vec3(std::sin(a), std::cos(2.0f * a), 1.0f)));
}

// `skin` exported from a character (rest frames unturned) dressed as described at the top.
inline std::size_t dress_as_foreign_rig(performer::SkinnedMesh& skin) {
  const std::size_t n = skin.joints.size();
  std::vector<glm::mat4> rest(n);
  performer::inverse_transforms(skin.inverse_bind, rest);
  std::vector<glm::quat> turn(n);
  for (std::size_t j = 0; j < n; ++j) turn[j] = test_rest_turn(j);
  std::vector<glm::mat4> turned_rest(n);
  for (std::size_t j = 0; j < n; ++j) {
    performer::SkinJoint& joint = skin.joints[j];
    const glm::quat above = joint.parent < 0 ? glm::quat(1, 0, 0, 0) : turn[static_cast<std::size_t>(joint.parent)];
    const glm::vec3 parent_at =
        joint.parent < 0 ? glm::vec3(0.0f) : glm::vec3(rest[static_cast<std::size_t>(joint.parent)][3]);
    joint.rotation = glm::inverse(above) * turn[j];
    joint.translation = glm::inverse(above) * (glm::vec3(rest[j][3]) - parent_at);
    turned_rest[j] = glm::translate(glm::mat4(1.0f), glm::vec3(rest[j][3])) * glm::mat4_cast(turn[j]);
  }
  performer::inverse_transforms(turned_rest, skin.inverse_bind);

  std::size_t elbow = n;
  for (std::size_t j = 0; j < n; ++j)
    if (skin.joints[j].name == "LeftElbow") elbow = j;
  for (performer::SkinJoint& joint : skin.joints) {
    std::string upper = joint.name;
    for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    joint.name = "mixamorig:" + upper;
  }
  if (elbow == n) return 0;
  performer::SkinJoint prop;
  prop.name = "Prop";
  prop.parent = static_cast<int>(elbow);
  prop.translation = glm::vec3(0.05f, 0.0f, 0.0f);
  prop.rotation = glm::angleAxis(1.0f, glm::vec3(0.0f, 1.0f, 0.0f));
  skin.joints.push_back(prop);
  const glm::mat4 prop_rest =
      turned_rest[elbow] * glm::translate(glm::mat4(1.0f), prop.translation) * glm::mat4_cast(prop.rotation);
  glm::mat4 prop_inverse;
  performer::inverse_transforms(std::span(&prop_rest, 1), std::span(&prop_inverse, 1));
  skin.inverse_bind.push_back(prop_inverse);
  std::size_t rebound = 0, seen = 0;
  for (std::size_t i = 0; i < skin.joint_indices.size(); ++i)
    if (skin.joint_indices[i] == elbow && skin.joint_weights[i] > 0.0f && seen++ % 2 == 0) {
      skin.joint_indices[i] = static_cast<std::uint16_t>(n);
      ++rebound;
    }
  return rebound;
}

// Builds the generated performer in metres for `skeleton` and writes it to `file` (.glb or .gltf)
// dressed as a foreign rig, with the face's targets as morph targets.
inline TestAvatar write_test_avatar(const performer::Skeleton& skeleton, const std::filesystem::path& file) {
  TestAvatar out;
  const float metres = performer::BodyMeshParams{}.meters_per_unit;
  performer::CharacterParams params;
  params.body.output_scale = metres;
  const performer::FaceModel head =
      performer::build_procedural_head(performer::load_viseme_set(performer::default_viseme_dir() / "visemes.tsv"));
  out.generated = performer::build_character(skeleton, head, params);
  out.skeleton_in_metres = skeleton;
  for (performer::Joint& j : out.skeleton_in_metres.joints) j.offset *= metres;
  performer::AvatarExport exported = performer::character_avatar(out.generated, skeleton);
  out.rebound_vertices = dress_as_foreign_rig(exported.skin);
  performer::write_gltf_skinned(file, exported.skin, exported.targets);
  return out;
}

}  // namespace test_support
