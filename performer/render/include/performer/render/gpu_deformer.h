// Equation 3.20 in a vertex shader (thesis 3.4.5, 3.5.5, 3.6): the face's deformation vectors
// (equations 3.9 and 3.11) on the head's vertices, then skeletal subspace deformation (3.17, 3.19)
// on every vertex, on the GPU. The character's streams are uploaded once, as the CPU jobs read them
// (character_deform.h): rest positions and normals, four joint indices and weights per vertex, and
// for the head range one position and one normal DV stream per face target. Each frame sends only
// the face weights of at most kFaceSlots active targets and the bone matrices (a uniform block, or a
// buffer texture when the skeleton has more joints than a uniform block holds).
//
// The deformed positions and normals are captured by transform feedback into one buffer, which a
// renderer draws from and tests read back to compare with the CPU reference.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "glcontext/context.h"
#include "glcontext/resources.h"
#include "performer/character.h"

namespace performer::render {

// Where the bone matrices go: a uniform block while they fit (GL_MAX_UNIFORM_BLOCK_SIZE, at least
// 16 KiB: 256 joints), else a buffer texture, which has no such limit.
enum class BoneStorage { automatic, uniform_block, buffer_texture };

class GpuDeformer {
 public:
  // The thesis' shader streams five DVs: two visemes, two expressions and a blink (the weight track
  // keeps at most that many channels active, weights_track.h).
  static constexpr int kFaceSlots = 5;

  // Uploads the character's streams into `context`, which must be current on this thread and
  // outlive the deformer. Throws std::invalid_argument for a character that is not valid
  // (character_problem), has more than 4 influences per vertex, or asks for a uniform block its
  // joints do not fit; glc::GlError for GL failures.
  GpuDeformer(glc::Context& context, const Character& character, BoneStorage storage = BoneStorage::automatic);

  // One frame of equation 3.20: `face_weights` one per target in Character::targets order,
  // `matrices` one per joint (skinning_matrices()). Throws std::invalid_argument for wrong counts or
  // more than kFaceSlots nonzero face weights.
  void deform(std::span<const float> face_weights, std::span<const glm::mat4> matrices);

  // Replaces the result with positions and normals computed elsewhere (the CPU jobs), so that the
  // renderer can draw a CPU-deformed frame the same way: the comparison of Table 3.9.
  void upload(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);

  // The last frame's result, read back from the GPU: vertex_count() positions and normals.
  void read_back(std::span<glm::vec3> positions, std::span<glm::vec3> normals) const;

  // Where the result lives: per vertex a position and a normal, 6 floats, interleaved.
  const glc::Buffer& output() const { return output_; }
  std::size_t vertex_count() const { return vertex_count_; }
  // "uniform block" or "buffer texture": where the bone matrices go.
  std::string bone_storage() const { return bones_in_texture_ ? "buffer texture" : "uniform block"; }

 private:
  glc::Context* context_;
  std::size_t vertex_count_ = 0;
  std::size_t head_first_ = 0, head_count_ = 0;
  std::size_t joint_count_ = 0, target_count_ = 0;
  bool bones_in_texture_ = false;
  glc::Program program_;
  GLint face_weights_location_ = -1, face_acting_location_ = -1;
  glc::Buffer rest_;      // position, normal per vertex
  glc::Buffer skin_;      // 4 x uint16 joints, 4 x float weights per vertex
  glc::Buffer face_dvs_;  // per target: head_count position DVs, then head_count normal DVs
  glc::Buffer bones_;     // the bone matrices (uniform or texture buffer)
  glc::Texture bone_texture_;
  glc::Buffer output_;
  // A 1x1 target to draw to: a headless context may have no default framebuffer, and GL refuses
  // draws (even with rasterisation discarded) without a complete one.
  glc::Texture target_texture_;
  glc::Framebuffer target_;
  glc::VertexArray body_vao_;  // every vertex, no DV attributes
  glc::VertexArray head_vao_;  // the head range, DV attributes pointed at each frame's targets
};

}  // namespace performer::render
