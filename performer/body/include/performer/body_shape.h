// The implicit body around a skeleton (the generated skin of body_mesh.h): one tapered capsule per
// bone, joined by a smooth union so that elbows, shoulders and hips blend instead of creasing.
//
// Radii come from the skeleton alone, so any BVH gets a plausible body: a bone is as thick as the
// square root of the share of the skeleton it carries (its own length plus everything below it).
// That one rule makes the spine thickest, thighs thicker than shins, upper arms thicker than
// forearms and hands and toes small, and it tapers every limb towards its tip. Bones whose subtree
// splits into two or more large limbs (the spine, which carries both arms and the neck) are the
// torso and get an extra factor.
//
// Limbs that only touch because of the rest pose (CMU's rest pose hangs the hands against the
// thighs) are kept apart: where two unrelated capsules are both nearly the closest, the field is
// pushed outside, leaving a thin gap along the surface halfway between them. Otherwise the skin of
// a thigh would sit next to the hand's joints and be bound to them. Two capsules are related when
// the path along the bones between them is shorter than their radii added (parent and child,
// siblings at one joint, the thigh and the spine at the hips).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "performer/skeleton.h"

namespace performer {

struct BodyShapeParams {
  // Capsule radius = thickness * size * sqrt(carried length / total bone length), where size is the
  // largest extent of the rest skeleton. 0.095 gives a human-like CMU figure (thigh about 8 cm).
  float thickness = 0.095f;
  float taper_exponent = 0.5f;  // the square root above; smaller evens thick and thin bones out
  float torso_factor = 1.2f;    // extra for bones carrying two or more large limbs
  // A child subtree counts as a large limb when it carries at least this share of the bone length.
  float limb_share = 0.1f;
  float min_radius = 0.012f;  // floor for fingers and toe tips, as a fraction of size
  float blend = 0.02f;        // smooth-union width as a fraction of size: wider fills joints more
  // Width of the gap kept between unrelated limbs, as a fraction of size (build_body_mesh widens it
  // to 1.5 grid cells when narrower, or the grid could not show it). 0 turns the separation off.
  float separation = 0.012f;
  // Bones on the way from the torso into the attach joint (the neck) are at least this thick, as a
  // fraction of size, so the separate head sits on a neck rather than a stalk.
  float neck_radius = 0.038f;
  // Bones from this joint and below are left out (empty: none), so that a separate head can be
  // attached at the joint. The bones leading into it keep their radius up to it instead of tapering.
  std::string exclude_from = "Head";
};

// One bone's solid: the points within radius(t) of the segment a-b, radius(t) varying linearly from
// radius_a at a (t = 0) to radius_b at b (t = 1), with round ends.
struct BoneCapsule {
  int parent = -1;  // the joint at a
  int joint = -1;   // the joint at b
  glm::vec3 a{0.0f}, b{0.0f};
  float radius_a = 0.0f, radius_b = 0.0f;
};

// Everything the field needs, in skeleton units.
struct BodyShape {
  std::vector<BoneCapsule> capsules;
  std::vector<std::uint8_t> related;  // capsules.size()^2 flags, 1 where two capsules may merge
  float blend = 0.0f;                 // smooth-union width
  float separation = 0.0f;            // gap between unrelated capsules; 0: none
};

// The capsules of every bone of nonzero length, given each joint's rest world position, and which
// of them are related. Bones from the joint named params.exclude_from (when the skeleton has it)
// and below are left out. Throws std::invalid_argument on a size mismatch, a parent that does not
// precede its child, or bad parameters.
BodyShape body_shape(const Skeleton& skeleton, std::span<const glm::vec3> rest_positions,
                     const BodyShapeParams& params);

// Largest extent of the joints' bounding box: the length every shape parameter is a fraction of.
float skeleton_size(std::span<const glm::vec3> rest_positions);

// The point of the bone's segment a-b nearest to p: its parameter t (0 at a, 1 at b) and distance.
struct BonePoint {
  float t = 0.0f;
  float distance = 0.0f;
};
BonePoint nearest_on_bone(const BoneCapsule& capsule, const glm::vec3& p);

// Signed distance-like field of one capsule: negative inside, 0 on the surface, about the distance
// outside (exact for equal radii, and close while the taper is gentle).
float capsule_field(const BoneCapsule& capsule, const glm::vec3& p);

// The body: capsule fields joined by a polynomial smooth minimum of width shape.blend, then cut
// apart where unrelated capsules meet (see above). Negative inside. Safe to call concurrently.
float body_field(const BodyShape& shape, const glm::vec3& p);

}  // namespace performer
