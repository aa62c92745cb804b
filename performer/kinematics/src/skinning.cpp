#include "performer/skinning.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "base/thread_pool.h"

namespace performer {

namespace {

constexpr std::size_t kSkinningVerticesPerChunk = 4096;

// The rows of one vertex range; everything is checked by the caller.
void skin_range(const SkinningJob& job, std::size_t begin, std::size_t end) {
  const auto slots = static_cast<std::size_t>(job.influences);
  const bool normals = !job.in_normals.empty();
  for (std::size_t v = begin; v < end; ++v) {
    // Blend the matrices first, then transform once: 3.17 read as (sum w_b S_b) v. Zero-weight slots
    // are padding and skipped.
    glm::mat4 blended(0.0f);
    for (std::size_t i = 0; i < slots; ++i) {
      const float w = job.joint_weights[v * slots + i];
      if (w == 0.0f) continue;
      const glm::mat4& s = job.matrices[job.joint_indices[v * slots + i]];
      blended[0] += w * s[0];
      blended[1] += w * s[1];
      blended[2] += w * s[2];
      blended[3] += w * s[3];
    }
    const glm::vec3 p = job.in_positions[v];
    // Affine blend: the bottom row of every S_b is (0 0 0 1) and the weights sum to 1, so w' = 1
    // and the projective divide is unnecessary.
    job.out_positions[v] =
        glm::vec3(blended[0]) * p.x + glm::vec3(blended[1]) * p.y + glm::vec3(blended[2]) * p.z + glm::vec3(blended[3]);
    if (!normals) continue;
    // Normals transform by the inverse-transpose of the linear part A. That equals cof(A) / det(A),
    // and since the result is renormalised only the sign of det(A) matters: the cofactor matrix
    // (columns a1 x a2, a2 x a0, a0 x a1) needs no division and degrades gracefully when A is
    // nearly singular (bones blended across a large angle).
    const glm::vec3 a0(blended[0]), a1(blended[1]), a2(blended[2]);
    const glm::vec3 c0 = glm::cross(a1, a2), c1 = glm::cross(a2, a0), c2 = glm::cross(a0, a1);
    const float det = glm::dot(a0, c0);
    const glm::vec3 n = job.in_normals[v];
    glm::vec3 out = c0 * n.x + c1 * n.y + c2 * n.z;
    if (det < 0.0f) out = -out;
    const float len = glm::length(out);
    // A collapsed blend has no meaningful normal; keeping the rest normal beats emitting NaN.
    job.out_normals[v] = len > 1e-20f ? out / len : n;
  }
}

}  // namespace

void skinning_matrices(std::span<const glm::mat4> world, std::span<const glm::mat4> inverse_rest_world,
                       std::span<glm::mat4> out) {
  if (world.size() != out.size() || inverse_rest_world.size() != out.size())
    throw std::invalid_argument("skinning_matrices: " + std::to_string(world.size()) + " world, " +
                                std::to_string(inverse_rest_world.size()) + " inverse rest and " +
                                std::to_string(out.size()) + " output matrices");
  for (std::size_t b = 0; b < out.size(); ++b) out[b] = world[b] * inverse_rest_world[b];
}

void inverse_transforms(std::span<const glm::mat4> in, std::span<glm::mat4> out) {
  if (in.size() != out.size())
    throw std::invalid_argument("inverse_transforms: " + std::to_string(in.size()) + " inputs, " +
                                std::to_string(out.size()) + " outputs");
  for (std::size_t b = 0; b < in.size(); ++b) out[b] = glm::mat4(glm::inverse(glm::dmat4(in[b])));
}

bool SkinningJob::valid() const {
  if (influences < 1) return false;
  const std::size_t n = in_positions.size();
  const std::size_t slots = n * static_cast<std::size_t>(influences);
  if (out_positions.size() != n || joint_indices.size() != slots || joint_weights.size() != slots) return false;
  if (in_normals.size() != out_normals.size()) return false;
  if (!in_normals.empty() && in_normals.size() != n) return false;
  for (const std::uint16_t index : joint_indices)
    if (index >= matrices.size()) return false;
  return true;
}

void skin(const SkinningJob& job) {
  if (!job.valid()) throw std::invalid_argument("skin: inconsistent job (stream sizes or a joint index out of range)");
  skin_range(job, 0, job.in_positions.size());
}

void skin_parallel(const SkinningJob& job, unsigned threads) {
  if (!job.valid()) throw std::invalid_argument("skin: inconsistent job (stream sizes or a joint index out of range)");
  base::parallel_for(job.in_positions.size(), kSkinningVerticesPerChunk, threads,
                     [&job](std::size_t begin, std::size_t end) { skin_range(job, begin, end); });
}

}  // namespace performer
