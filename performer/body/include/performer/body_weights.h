// SSD weights for the generated body (body_shape.h, body_mesh.h), bound along the skeleton rather
// than across space (thesis 3.5.4, equation 3.18's form kept for the seeds). Equation 3.18 alone weighs every
// joint by its distance to the vertex, so skin is pulled by bones that are near in the rest pose
// but far apart on the skeleton (a hand hanging by the thigh, the upper arm against the chest), and
// tears in motion. Here each vertex first finds the bone it was grown from (the capsule whose field
// is lowest at it), and only that bone and the bones next to it along the skeleton seed its
// weights; a diffusion over the surface then blends them where bones meet.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "performer/body_shape.h"
#include "performer/ssd_weights.h"

namespace performer {

struct BodyWeightParams {
  // Seeds: each candidate bone weighs 1 / d^falloff, d the distance from the vertex to the bone's
  // segment (equation 3.18's form, measured to the bone rather than to a joint). A steep falloff
  // makes the seeds close to a segmentation by nearest bone, and leaves the blending to the
  // diffusion, which spreads it along the surface evenly; equation 3.18's own n = 2 blends through
  // the volume instead, and over the thick torso reaches skin that should not follow. Measured on
  // the CMU clips (SkinHoldsTogetherInMotion): falloff 2 with 40 steps leaves 0.3-0.6 % of edges
  // stretched beyond twice their length and the worst 4.7-5x; 60 with 150 steps 0.04-0.05 % and 3x.
  float falloff = 60.0f;
  float min_distance = 1e-4f;  // distances are clamped to at least this (skeleton units)
  // Diffusion steps over the mesh, each w <- (w + mean of the edge neighbours' w) / 2: a blend about
  // sqrt(steps) edges wide on either side of each seam between bones.
  int smoothing_steps = 150;
  int max_influences = 4;  // joints kept per vertex, 1..kMaxInfluences
};

// Seeds: for each vertex of rest_positions (in `scale` units per skeleton unit;
// BodyMesh::output_scale), its own capsule (lowest capsule_field) and the capsules of its parent
// bone (ending at its first joint) and child bones (starting at its second joint) are candidates;
// each weighs as BodyWeightParams says, and its weight goes to the joint that moves it
// (BoneCapsule::parent), a joint moving several candidates taking the largest.
// Then params.smoothing_steps steps of diffusion over the mesh (`triangles`, indices into
// rest_positions). Finally the max_influences strongest joints are kept, normalised to sum 1.
// Output slots as ssd_weights (joint indices are skeleton joint indices; unused slots joint 0,
// weight 0). Threads over vertex ranges. Throws std::invalid_argument for bad parameters
// (falloff negative, min_distance not positive, smoothing_steps negative, max_influences out of
// range), a shape without capsules, a scale that is not positive, or mis-sized outputs.
void body_ssd_weights(const BodyShape& shape, std::span<const glm::vec3> rest_positions,
                      std::span<const std::uint32_t> triangles, float scale, const BodyWeightParams& params,
                      std::span<std::uint16_t> out_joints, std::span<float> out_weights, unsigned threads = 0);

}  // namespace performer
