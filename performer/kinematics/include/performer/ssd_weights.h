// Skeletal subspace deformation, bind step (thesis 3.5.4, equation 3.18): which bones move each
// vertex, and how much. Done once per mesh, in the rest (neutral) pose.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace performer {

// Upper bound on influences per vertex: keeps the per-vertex selection on the stack, and is already
// twice what vertex-attribute budgets usually allow.
inline constexpr int kMaxInfluences = 8;

struct SsdWeightParams {
  // Equation 3.18, w = k / |v - J|^n. k scales every weight alike, so it cancels when the weights
  // are normalised; it is kept so the parameters read like the thesis.
  float k = 1.0f;
  float n = 2.0f;          // fall-off: larger n hands a vertex more completely to its nearest joints
  int max_influences = 4;  // slots per vertex, 1..kMaxInfluences
  // Distances are clamped to at least this, so a vertex sitting on a joint gets a large finite
  // weight rather than a division by zero.
  float min_distance = 1e-4f;
};

// For each vertex, the max_influences joints with the largest weight (3.18), normalised to sum 1.
// rest_positions: the mesh in its neutral pose. joint_positions: joint b's rest world position
// (e.g. column 3 of its rest world transform); bone index b in the output refers to this array, and
// to the skinning matrix array later. Leave out joints that should not pull on skin (end sites) by
// passing a filtered array and mapping indices yourself.
// out_joints / out_weights: vertex v's slots are [v * max_influences, (v + 1) * max_influences),
// strongest first; slots beyond the joint count get joint 0 and weight 0. Ties go to the lower index.
// Threads over vertex ranges (threads 0: hardware concurrency). Throws std::invalid_argument on bad
// parameters (k <= 0, n < 0, max_influences out of range), no joints, or size mismatches.
void ssd_weights(std::span<const glm::vec3> rest_positions, std::span<const glm::vec3> joint_positions,
                 const SsdWeightParams& params, std::span<std::uint16_t> out_joints, std::span<float> out_weights,
                 unsigned threads = 0);

}  // namespace performer
