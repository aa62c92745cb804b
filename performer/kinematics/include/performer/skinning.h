// Skeletal subspace deformation, per-frame step (thesis 3.5.4-3.5.5): every vertex moved by the
// weighted blend of its bones' transforms, equation 3.17, and its normal by equation 3.19.
//
// The data is laid out as the thesis' vertex shader consumes it: positions and normals as streams,
// bone indices and weights as two more per-vertex streams (fixed slots per vertex), and the bone
// matrices as one small array shared by all vertices (the shader's constant memory).
#pragma once

#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace performer {

// The per-bone matrices of equation 3.17, S_b = M_b * B_b^-1: M_b the bone's current world
// transform, B_b its rest world transform. The thesis states 3.17 in a frame where the neutral pose
// has T_b = I; S_b is exactly that T_b for a mesh modelled in world space around the rest skeleton.
// Sizes must match (std::invalid_argument otherwise).
void skinning_matrices(std::span<const glm::mat4> world, std::span<const glm::mat4> inverse_rest_world,
                       std::span<glm::mat4> out);

// out[b] = in[b]^-1, computed in double: rest transforms are inverted once per mesh, and a sloppy
// inverse would show up as the rest pose not reproducing the mesh.
void inverse_transforms(std::span<const glm::mat4> in, std::span<glm::mat4> out);

// One skinning pass: plain views of the streams, owning nothing.
struct SkinningJob {
  int influences = 4;                            // slots per vertex in joint_indices / joint_weights
  std::span<const glm::mat4> matrices;           // skinning_matrices() output, indexed by bone
  std::span<const std::uint16_t> joint_indices;  // vertex_count * influences
  std::span<const float> joint_weights;          // vertex_count * influences, each vertex summing to 1
  std::span<const glm::vec3> in_positions;       // rest (neutral) pose
  std::span<glm::vec3> out_positions;            // may be the same memory as in_positions
  std::span<const glm::vec3> in_normals;         // empty to skip normals
  std::span<glm::vec3> out_normals;              // empty exactly when in_normals is

  // Sizes agree and every index names a matrix. Cost is one pass over the indices.
  bool valid() const;
};

// Equation 3.17: v' = (sum_b w_b S_b) v. Equation 3.19 with the exact normal transform: n' is the
// normalised inverse-transpose of the blended 3x3 part applied to n (the thesis uses the blended 3x3
// itself, which is the same for a rigid bone but shears normals where bones blend).
// Throws std::invalid_argument when !job.valid().
void skin(const SkinningJob& job);

// skin() over vertex chunks on up to `threads` threads (0: hardware concurrency). Identical output.
void skin_parallel(const SkinningJob& job, unsigned threads = 0);

}  // namespace performer
