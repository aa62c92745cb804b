// A glTF avatar (gltf_avatar.h) as the performer: its skinned mesh and face made into a Character
// (character.h), so that equation 3.20's CPU jobs and the vertex shader deform it unchanged, and its
// joints posed by a BVH clip's, matched by name.
//
// Posing (retargeting): a BVH skeleton's rest pose has every rotation zero, so a BVH joint's world
// rotation in a frame is its rotation away from rest, in world axes. An avatar joint matched to it
// turns by that same world rotation about its own position, and keeps its own bone lengths: its
// position follows its parent's motion, except for the topmost matched joints (the hips, usually),
// which move as their BVH joints move from rest, scaled to the avatar's size. An unmatched joint
// keeps its bind pose relative to its parent (it moves rigidly with the nearest matched ancestor;
// above every matched joint it stays put). This assumes the avatar and the clip share their axes
// (glTF and BVH are both +Y up; the figures face +Z at rest) and stand alike at rest: an avatar in an
// A-pose driven by a T-pose clip keeps its arms as much lower as its rest pose has them.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "performer/character.h"
#include "performer/face_model.h"
#include "performer/skeleton.h"
#include "performer/skinned_mesh.h"

namespace performer {

// The avatar as equation 3.20 consumes it. The mesh is the skin's; its joints' inverse binds are the
// Character's. More than 4 influences per vertex are cut to the 4 strongest (ties to the lower slot),
// renormalised, as the vertex shader streams 4. The face range runs from the first vertex that some
// target moves to the end of the mesh (the renderer shades the vertices from head_first on as skin),
// and the targets are `face`'s, cut to that range. head_joint is -1 and head_placement the identity:
// the face is skinned by the avatar's own weights, in the avatar's frame. Throws
// std::invalid_argument when the skin is inconsistent (skinned_mesh_problem) or `face` does not
// have the skin's vertex count.
Character avatar_character(const SkinnedMesh& skin, const FaceModel& face);

// How an avatar's joints follow a BVH skeleton (see the top of this file).
struct AvatarRetarget {
  std::vector<int> skeleton_joint;       // per avatar joint: the BVH joint it follows, -1 for none
  std::vector<int> parent;               // per avatar joint: its parent joint, -1 for a root
  std::vector<int> order;                // avatar joints, parents before children
  std::vector<bool> anchor;              // matched, with no matched ancestor: moves as its BVH joint
  std::vector<glm::mat4> rest_world;     // per avatar joint: its world transform in the rest pose
  std::vector<glm::vec3> skeleton_rest;  // per avatar joint: its BVH joint's rest position (anchors)
  float scale = 1.0f;                    // avatar units per BVH unit
  std::vector<std::string> unmatched;    // avatar joints that follow no BVH joint, in joint order
  int root = -1;                         // the first anchor: what a camera follows; -1 with no match
};

// Matches each avatar joint to the BVH joint of the same name, ignoring case and a namespace prefix
// up to the last ':' ("mixamorig:Hips" is Hips). The scale is the ratio of the spreads (RMS distance
// from their centroid) of the matched joints' rest positions, avatar over BVH; 1 with fewer than two
// matches. Throws std::invalid_argument for an inconsistent joint hierarchy (skin_world_transforms).
AvatarRetarget retarget_by_name(const SkinnedMesh& avatar, const Skeleton& skeleton);

// The avatar's joint world transforms for the BVH pose `skeleton_world` (world_transforms() of a
// motion row), for skinning_matrices() with the avatar's inverse binds. Throws std::invalid_argument
// on size mismatches.
void retarget_pose(const AvatarRetarget& retarget, std::span<const glm::mat4> skeleton_world,
                   std::span<glm::mat4> out_world);

// The generated performer (build_character) as a glTF avatar, for write_gltf_skinned: the skin's
// joints are the skeleton's (names, hierarchy, rest offsets in the character's units, no rotation),
// its inverse binds and weights the character's; the face's targets spread over the whole mesh (zero
// off the head). Such an avatar retargets onto its own skeleton exactly: the same skinning matrices
// up to rounding. Throws std::invalid_argument when character_problem() finds one or the skeleton
// does not have one joint per inverse bind matrix.
struct AvatarExport {
  SkinnedMesh skin;
  std::vector<MorphTarget> targets;
};
AvatarExport character_avatar(const Character& character, const Skeleton& skeleton);

}  // namespace performer
