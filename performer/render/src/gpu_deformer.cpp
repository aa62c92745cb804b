#include "performer/render/gpu_deformer.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "deform_shader.h"
#include "glcontext/error.h"

namespace performer::render {

namespace {

constexpr GLuint kBonesBinding = 0;  // uniform block binding point of the bone matrices
constexpr std::size_t kRestStride = 6 * sizeof(float);
struct SkinVertex {
  std::uint16_t joints[4];
  float weights[4];
};
static_assert(sizeof(SkinVertex) == 24);
constexpr std::size_t kOutputStride = 6 * sizeof(float);

// The attributes both vertex arrays share, starting at vertex `first`.
void point_base_attributes(const glc::GlApi& gl, const glc::Buffer& rest, const glc::Buffer& skin, std::size_t first) {
  gl.glBindBuffer(GL_ARRAY_BUFFER, rest.id());
  gl.glEnableVertexAttribArray(kRestPositionAttribute);
  gl.glVertexAttribPointer(kRestPositionAttribute, 3, GL_FLOAT, GL_FALSE, kRestStride,
                           glc::buffer_offset(first * kRestStride));
  gl.glEnableVertexAttribArray(kRestNormalAttribute);
  gl.glVertexAttribPointer(kRestNormalAttribute, 3, GL_FLOAT, GL_FALSE, kRestStride,
                           glc::buffer_offset(first * kRestStride + 3 * sizeof(float)));
  gl.glBindBuffer(GL_ARRAY_BUFFER, skin.id());
  gl.glEnableVertexAttribArray(kJointsAttribute);
  gl.glVertexAttribIPointer(kJointsAttribute, 4, GL_UNSIGNED_SHORT, sizeof(SkinVertex),
                            glc::buffer_offset(first * sizeof(SkinVertex)));
  gl.glEnableVertexAttribArray(kWeightsAttribute);
  gl.glVertexAttribPointer(kWeightsAttribute, 4, GL_FLOAT, GL_FALSE, sizeof(SkinVertex),
                           glc::buffer_offset(first * sizeof(SkinVertex) + offsetof(SkinVertex, weights)));
}

}  // namespace

GpuDeformer::GpuDeformer(glc::Context& context, const Character& character, BoneStorage storage) : context_(&context) {
  const std::string problem = character_problem(character);
  if (!problem.empty()) throw std::invalid_argument("GpuDeformer: the character is not valid: " + problem);
  if (character.influences > 4)
    throw std::invalid_argument("GpuDeformer: " + std::to_string(character.influences) +
                                " influences per vertex; the shader takes 4");
  const glc::GlApi& gl = context.gl();
  vertex_count_ = character.vertex_count();
  head_first_ = character.head_first;
  head_count_ = character.head_count;
  joint_count_ = character.inverse_bind.size();
  target_count_ = character.targets.size();

  // Bone matrices: a uniform block while they fit, else a buffer texture.
  GLint max_block = 0;
  gl.glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &max_block);
  const bool fits = joint_count_ * sizeof(glm::mat4) <= static_cast<std::size_t>(max_block);
  if (storage == BoneStorage::uniform_block && !fits)
    throw std::invalid_argument("GpuDeformer: " + std::to_string(joint_count_) +
                                " joints do not fit a uniform block of " + std::to_string(max_block) + " bytes");
  bones_in_texture_ = storage == BoneStorage::buffer_texture || (storage == BoneStorage::automatic && !fits);
  static constexpr std::array<const char*, 2> kVaryings = {"v_position", "v_normal"};
  program_ = glc::Program::link_capture(gl, deform_vertex_shader(joint_count_, bones_in_texture_, kFaceSlots),
                                        kVaryings, "equation 3.20");
  face_weights_location_ = program_.uniform("u_face_weights");
  face_acting_location_ = program_.uniform("u_face_acting");
  program_.use();
  if (bones_in_texture_) {
    gl.glUniform1i(program_.uniform("u_bone_texels"), 0);
  } else {
    const GLuint block = gl.glGetUniformBlockIndex(program_.id(), "Bones");
    if (block == GL_INVALID_INDEX) throw glc::GlError("equation 3.20: the shader has no Bones block");
    gl.glUniformBlockBinding(program_.id(), block, kBonesBinding);
  }

  // The streams, as the CPU jobs read them: rest position and normal interleaved; joints and
  // weights padded to 4 slots; per target its head-range position DVs, then its normal DVs.
  std::vector<float> rest(vertex_count_ * 6);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    std::memcpy(&rest[v * 6], &character.mesh.positions[v], 3 * sizeof(float));
    std::memcpy(&rest[v * 6 + 3], &character.mesh.normals[v], 3 * sizeof(float));
  }
  rest_ = glc::Buffer::create(gl, GL_ARRAY_BUFFER, rest.size() * sizeof(float), rest.data(), GL_STATIC_DRAW);
  std::vector<SkinVertex> skin(vertex_count_, SkinVertex{{0, 0, 0, 0}, {0, 0, 0, 0}});
  const auto slots = static_cast<std::size_t>(character.influences);
  for (std::size_t v = 0; v < vertex_count_; ++v)
    for (std::size_t k = 0; k < slots; ++k) {
      skin[v].joints[k] = character.joint_indices[v * slots + k];
      skin[v].weights[k] = character.joint_weights[v * slots + k];
    }
  skin_ = glc::Buffer::create(gl, GL_ARRAY_BUFFER, skin.size() * sizeof(SkinVertex), skin.data(), GL_STATIC_DRAW);
  std::vector<glm::vec3> dvs;
  dvs.reserve(target_count_ * head_count_ * 2);
  for (const MorphTarget& t : character.targets) {
    dvs.insert(dvs.end(), t.position_deltas.begin(), t.position_deltas.end());
    dvs.insert(dvs.end(), t.normal_deltas.begin(), t.normal_deltas.end());
  }
  face_dvs_ = glc::Buffer::create(gl, GL_ARRAY_BUFFER, std::max<std::size_t>(dvs.size(), 1) * sizeof(glm::vec3),
                                  dvs.empty() ? nullptr : dvs.data(), GL_STATIC_DRAW);
  bones_ = glc::Buffer::create(gl, bones_in_texture_ ? GL_TEXTURE_BUFFER : GL_UNIFORM_BUFFER,
                               std::max<std::size_t>(joint_count_, 1) * sizeof(glm::mat4), nullptr, GL_STREAM_DRAW);
  if (bones_in_texture_) {
    bone_texture_ = glc::Texture::create(gl);
    gl.glBindTexture(GL_TEXTURE_BUFFER, bone_texture_.id());
    gl.glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, bones_.id());
  }
  output_ = glc::Buffer::create(gl, GL_TRANSFORM_FEEDBACK_BUFFER,
                                std::max<std::size_t>(vertex_count_, 1) * kOutputStride, nullptr, GL_DYNAMIC_COPY);

  target_texture_ = glc::Texture::create_2d(gl, 1, 1, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  target_ = glc::Framebuffer::create(gl);
  target_.attach_color(target_texture_);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);

  body_vao_ = glc::VertexArray::create(gl);
  body_vao_.bind();
  point_base_attributes(gl, rest_, skin_, 0);
  head_vao_ = glc::VertexArray::create(gl);
  head_vao_.bind();
  point_base_attributes(gl, rest_, skin_, head_first_);
  gl.glBindVertexArray(0);
  glc::check(gl, "GpuDeformer: upload");
}

void GpuDeformer::deform(std::span<const float> face_weights, std::span<const glm::mat4> matrices) {
  if (face_weights.size() != target_count_)
    throw std::invalid_argument("GpuDeformer::deform: " + std::to_string(face_weights.size()) + " face weights for " +
                                std::to_string(target_count_) + " targets");
  if (matrices.size() != joint_count_)
    throw std::invalid_argument("GpuDeformer::deform: " + std::to_string(matrices.size()) + " matrices for " +
                                std::to_string(joint_count_) + " joints");
  // The acting targets, in target order (the CPU adds them in that order).
  std::array<std::size_t, kFaceSlots> active{};
  std::array<float, kFaceSlots> weights{};
  int acting = 0;
  for (std::size_t t = 0; t < face_weights.size(); ++t) {
    if (face_weights[t] == 0.0f) continue;
    if (acting == kFaceSlots)
      throw std::invalid_argument("GpuDeformer::deform: more than " + std::to_string(kFaceSlots) +
                                  " face targets act at once; the shader streams " + std::to_string(kFaceSlots));
    active[static_cast<std::size_t>(acting)] = t;
    weights[static_cast<std::size_t>(acting)] = face_weights[t];
    ++acting;
  }

  const glc::GlApi& gl = context_->gl();
  program_.use();
  target_.bind();
  if (bones_in_texture_) {
    gl.glBindBuffer(GL_TEXTURE_BUFFER, bones_.id());
    gl.glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(matrices.size_bytes()), matrices.data());
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glBindTexture(GL_TEXTURE_BUFFER, bone_texture_.id());
  } else {
    gl.glBindBuffer(GL_UNIFORM_BUFFER, bones_.id());
    gl.glBufferSubData(GL_UNIFORM_BUFFER, 0, static_cast<GLsizeiptr>(matrices.size_bytes()), matrices.data());
    gl.glBindBufferBase(GL_UNIFORM_BUFFER, kBonesBinding, bones_.id());
  }
  gl.glEnable(GL_RASTERIZER_DISCARD);

  // Every vertex skinned from the rest streams (the body's result; the head's is replaced below).
  const std::array<float, kFaceSlots> none{};
  gl.glUniform1fv(face_weights_location_, kFaceSlots, none.data());
  gl.glUniform1i(face_acting_location_, 0);
  body_vao_.bind();
  gl.glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output_.id(), 0,
                       static_cast<GLsizeiptr>(vertex_count_ * kOutputStride));
  gl.glBeginTransformFeedback(GL_POINTS);
  gl.glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(vertex_count_));
  gl.glEndTransformFeedback();

  // The head: its DVs first, then the same skinning, into the head's range of the output.
  if (head_count_ > 0) {
    head_vao_.bind();
    gl.glBindBuffer(GL_ARRAY_BUFFER, face_dvs_.id());
    for (int s = 0; s < kFaceSlots; ++s) {
      const GLuint position_slot = kFirstPositionDvAttribute + static_cast<GLuint>(s);
      const GLuint normal_slot = position_slot + static_cast<GLuint>(kFaceSlots);
      if (s >= acting) {
        // A disabled attribute reads (0, 0, 0); its weight is 0 anyway.
        gl.glDisableVertexAttribArray(position_slot);
        gl.glDisableVertexAttribArray(normal_slot);
        continue;
      }
      const std::size_t target = active[static_cast<std::size_t>(s)];
      const std::size_t first = target * 2 * head_count_ * sizeof(glm::vec3);
      gl.glEnableVertexAttribArray(position_slot);
      gl.glVertexAttribPointer(position_slot, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), glc::buffer_offset(first));
      gl.glEnableVertexAttribArray(normal_slot);
      gl.glVertexAttribPointer(normal_slot, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3),
                               glc::buffer_offset(first + head_count_ * sizeof(glm::vec3)));
    }
    gl.glUniform1fv(face_weights_location_, kFaceSlots, weights.data());
    gl.glUniform1i(face_acting_location_, acting > 0 ? 1 : 0);
    gl.glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output_.id(),
                         static_cast<GLintptr>(head_first_ * kOutputStride),
                         static_cast<GLsizeiptr>(head_count_ * kOutputStride));
    gl.glBeginTransformFeedback(GL_POINTS);
    gl.glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(head_count_));
    gl.glEndTransformFeedback();
  }
  gl.glDisable(GL_RASTERIZER_DISCARD);
  gl.glBindVertexArray(0);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glc::check(gl, "GpuDeformer::deform");
}

void GpuDeformer::upload(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
  if (positions.size() != vertex_count_ || normals.size() != vertex_count_)
    throw std::invalid_argument("GpuDeformer::upload: " + std::to_string(positions.size()) + " positions and " +
                                std::to_string(normals.size()) + " normals for " + std::to_string(vertex_count_) +
                                " vertices");
  std::vector<float> interleaved(vertex_count_ * 6);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    std::memcpy(&interleaved[v * 6], &positions[v], 3 * sizeof(float));
    std::memcpy(&interleaved[v * 6 + 3], &normals[v], 3 * sizeof(float));
  }
  const glc::GlApi& gl = context_->gl();
  gl.glBindBuffer(GL_ARRAY_BUFFER, output_.id());
  gl.glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                     interleaved.data());
  glc::check(gl, "GpuDeformer::upload");
}

void GpuDeformer::read_back(std::span<glm::vec3> positions, std::span<glm::vec3> normals) const {
  if (positions.size() != vertex_count_ || normals.size() != vertex_count_)
    throw std::invalid_argument("GpuDeformer::read_back: room for " + std::to_string(positions.size()) +
                                " positions and " + std::to_string(normals.size()) + " normals, " +
                                std::to_string(vertex_count_) + " vertices");
  const glc::GlApi& gl = context_->gl();
  std::vector<float> out(vertex_count_ * 6);
  gl.glBindBuffer(GL_COPY_READ_BUFFER, output_.id());
  gl.glGetBufferSubData(GL_COPY_READ_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)), out.data());
  glc::check(gl, "GpuDeformer::read_back");
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    positions[v] = glm::vec3(out[v * 6], out[v * 6 + 1], out[v * 6 + 2]);
    normals[v] = glm::vec3(out[v * 6 + 3], out[v * 6 + 4], out[v * 6 + 5]);
  }
}

}  // namespace performer::render
