#include "performer/render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

#include "glcontext/error.h"
#include "imageio/read.h"
#include "render_shaders.h"

namespace performer::render {

namespace {

constexpr int kHairShells = 16;
constexpr float kHairStrandsPerMetre = 420.0f;
constexpr GLuint kHairAttribute = 2;

}  // namespace

std::filesystem::path cubemap_face_file(const std::filesystem::path& dir, const std::string& face) {
  for (const char* ext : {".jpg", ".png", ".ppm"})
    if (const std::filesystem::path candidate = dir / (face + ext); std::filesystem::exists(candidate))
      return candidate;
  return {};
}

namespace {

// The six faces in GL's order (+X, -X, +Y, -Y, +Z, -Z).
glc::Texture load_cubemap(const glc::GlApi& gl, const std::filesystem::path& dir) {
  static constexpr std::array<const char*, 6> kFaces = {"posx", "negx", "posy", "negy", "posz", "negz"};
  glc::Texture texture = glc::Texture::create(gl);
  gl.glBindTexture(GL_TEXTURE_CUBE_MAP, texture.id());
  for (int f = 0; f < 6; ++f) {
    const std::filesystem::path file = cubemap_face_file(dir, kFaces[static_cast<std::size_t>(f)]);
    if (file.empty())
      throw std::invalid_argument("cube map: no " + std::string(kFaces[static_cast<std::size_t>(f)]) +
                                  ".jpg, .png or .ppm in " + dir.string());
    const imageio::Image image = imageio::read_image(file.string());
    if (image.width != image.height || image.channels < 3)
      throw std::invalid_argument("cube map face " + file.string() + ": expected a square RGB image, got " +
                                  std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                                  std::to_string(image.channels) + " channels");
    const float scale = image.is_float ? 255.0f : 255.0f / static_cast<float>((1 << image.bits_per_sample) - 1);
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
    // Rows go in bottom first. The faces are pictures with the sky at the top of the side faces,
    // and OpenGL's cube map face rules (the t axis of a side face runs along -Y from its first row)
    // would otherwise show them upside down; the render test checks the sky is above the horizon.
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int c = 0; c < 3; ++c)
          rgb[(static_cast<std::size_t>(image.height - 1 - y) * static_cast<std::size_t>(image.width) +
               static_cast<std::size_t>(x)) *
                  3 +
              static_cast<std::size_t>(c)] =
              static_cast<std::uint8_t>(std::clamp(image.at(x, y, c) * scale + 0.5f, 0.0f, 255.0f));
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f), 0, GL_RGB8, image.width, image.height, 0,
                    GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  }
  gl.glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  gl.glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
  glc::check(gl, "cube map upload");
  return texture;
}

// Per vertex: the head's rest position in the head model's frame and the hair density there (the
// scalp: the top of the head and its back, never the face); zero on the body.
std::vector<glm::vec4> hair_attributes(const Character& c) {
  std::vector<glm::vec4> out(c.vertex_count(), glm::vec4(0.0f));
  if (c.head_count == 0) return out;
  const glm::mat4 to_model = glm::inverse(c.head_placement);
  glm::vec3 lo(1e30f), hi(-1e30f);
  std::vector<glm::vec3> model(c.head_count);
  for (std::size_t i = 0; i < c.head_count; ++i) {
    model[i] = glm::vec3(to_model * glm::vec4(c.mesh.positions[c.head_first + i], 1.0f));
    lo = glm::min(lo, model[i]);
    hi = glm::max(hi, model[i]);
  }
  const glm::vec3 span = glm::max(hi - lo, glm::vec3(1e-6f));
  for (std::size_t i = 0; i < c.head_count; ++i) {
    const glm::vec3 r = (model[i] - lo) / span;  // 0..1 in the head's box; +Z is the face
    auto ramp = [](float a, float b, float x) { return std::clamp((x - a) / (b - a), 0.0f, 1.0f); };
    float density = std::max(ramp(0.66f, 0.76f, r.y), ramp(0.62f, 0.4f, r.z) * ramp(0.3f, 0.45f, r.y));
    if (r.z > 0.7f && r.y < 0.78f) density = 0.0f;  // the face
    out[c.head_first + i] = glm::vec4(model[i], 0.85f * density);
  }
  return out;
}

}  // namespace

Renderer::Renderer(glc::Context& context, const Character& character, const RenderSettings& settings)
    : context_(&context), character_(&character), settings_(settings) {
  if (settings.width < 16 || settings.height < 16 || settings.width > 8192 || settings.height > 8192)
    throw std::invalid_argument("render size " + std::to_string(settings.width) + "x" +
                                std::to_string(settings.height) + " outside 16x16..8192x8192");
  const glc::GlApi& gl = context.gl();
  color_ = glc::Renderbuffer::create(gl, settings.width, settings.height, GL_RGBA8, settings.samples);
  depth_ = glc::Renderbuffer::create(gl, settings.width, settings.height, GL_DEPTH_COMPONENT24, settings.samples);
  samples_ = color_.samples();
  scene_fbo_ = glc::Framebuffer::create(gl);
  scene_fbo_.attach(GL_COLOR_ATTACHMENT0, color_, false);
  scene_fbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
  resolved_ = glc::Renderbuffer::create(gl, settings.width, settings.height, GL_RGBA8, 0);
  resolve_fbo_ = glc::Framebuffer::create(gl);
  resolve_fbo_.attach(GL_COLOR_ATTACHMENT0, resolved_);

  character_program_ = glc::Program::link(gl, shaders::kCharacterVertex, shaders::kCharacterFragment, "character");
  outline_program_ = glc::Program::link(gl, shaders::kCharacterVertex, shaders::kOutlineFragment, "outline");
  hair_program_ = glc::Program::link(gl, shaders::kCharacterVertex, shaders::kHairFragment, "hair");
  sky_program_ = glc::Program::link(gl, shaders::kSkyVertex, shaders::kSkyFragment, "environment");
  floor_program_ = glc::Program::link(gl, shaders::kFloorVertex, shaders::kFloorFragment, "floor");
  snow_program_ = glc::Program::link(gl, shaders::kSnowVertex, shaders::kSnowFragment, "snow");

  const auto& indices = character.mesh.indices;
  indices_ = glc::Buffer::create(gl, GL_ELEMENT_ARRAY_BUFFER, indices.size() * sizeof(std::uint32_t), indices.data(),
                                 GL_STATIC_DRAW);
  const std::vector<glm::vec4> hair = hair_attributes(character);
  hair_attributes_ =
      glc::Buffer::create(gl, GL_ARRAY_BUFFER, hair.size() * sizeof(glm::vec4), hair.data(), GL_STATIC_DRAW);
  // The shells are drawn over the scalp's triangles only (any corner with hair), kept in their own
  // index buffer: every shell re-draws them, and the rest of the head would only be discarded.
  std::vector<std::uint32_t> scalp;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    if (hair[indices[t]].w > 0.0f || hair[indices[t + 1]].w > 0.0f || hair[indices[t + 2]].w > 0.0f)
      scalp.insert(scalp.end(), {indices[t], indices[t + 1], indices[t + 2]});
  scalp_index_count_ = scalp.size();
  // Strands as long as 9 % of the head's height.
  float head_lo = 1e30f, head_hi = -1e30f;
  for (std::size_t v = character.head_first; v < character.vertex_count(); ++v) {
    head_lo = std::min(head_lo, character.mesh.positions[v].y);
    head_hi = std::max(head_hi, character.mesh.positions[v].y);
  }
  hair_length_ = character.head_count > 0 ? 0.09f * (head_hi - head_lo) : 0.0f;
  scalp_indices_ =
      glc::Buffer::create(gl, GL_ELEMENT_ARRAY_BUFFER, std::max<std::size_t>(scalp.size(), 1) * sizeof(std::uint32_t),
                          scalp.empty() ? nullptr : scalp.data(), GL_STATIC_DRAW);
  character_vao_ = glc::VertexArray::create(gl);
  sky_vao_ = glc::VertexArray::create(gl);
  static constexpr std::array<float, 8> kCorners = {-1, -1, 1, -1, -1, 1, 1, 1};
  floor_corners_ = glc::Buffer::create(gl, GL_ARRAY_BUFFER, sizeof(kCorners), kCorners.data(), GL_STATIC_DRAW);
  floor_vao_ = glc::VertexArray::create(gl);
  floor_vao_.bind();
  gl.glEnableVertexAttribArray(0);
  gl.glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  snow_instances_ = glc::Buffer::create(gl, GL_ARRAY_BUFFER, sizeof(glm::vec4), nullptr, GL_STREAM_DRAW);
  snow_vao_ = glc::VertexArray::create(gl);
  gl.glBindVertexArray(0);
  if (settings.effects.environment) cubemap_ = load_cubemap(gl, settings.cubemap_dir);
  glc::check(gl, "Renderer setup");
}

void Renderer::draw_environment(const Camera& camera) {
  const glc::GlApi& gl = context_->gl();
  const Effects& fx = settings_.effects;
  const float aspect = static_cast<float>(settings_.width) / static_cast<float>(settings_.height);
  const glm::mat4 view_projection = camera.projection(aspect) * camera.view();
  scene_fbo_.bind();
  gl.glViewport(0, 0, settings_.width, settings_.height);
  gl.glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (fx.environment) {
    gl.glActiveTexture(GL_TEXTURE0);
    gl.glBindTexture(GL_TEXTURE_CUBE_MAP, cubemap_.id());
  }
  // The environment sphere (or sky), behind everything.
  gl.glDisable(GL_DEPTH_TEST);
  gl.glDisable(GL_CULL_FACE);
  gl.glDisable(GL_BLEND);
  sky_program_.use();
  gl.glUniformMatrix4fv(sky_program_.uniform("u_inverse_view_projection"), 1, GL_FALSE,
                        glm::value_ptr(glm::inverse(view_projection)));
  gl.glUniform3fv(sky_program_.uniform("u_eye"), 1, glm::value_ptr(camera.eye));
  gl.glUniform1i(sky_program_.uniform("u_environment"), fx.environment ? 1 : 0);
  gl.glUniform1i(sky_program_.uniform("u_cubemap"), 0);
  sky_vao_.bind();
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Renderer::resolve() {
  const glc::GlApi& gl = context_->gl();
  gl.glBindVertexArray(0);
  gl.glBindFramebuffer(GL_READ_FRAMEBUFFER, scene_fbo_.id());
  gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_.id());
  gl.glBlitFramebuffer(0, 0, settings_.width, settings_.height, 0, 0, settings_.width, settings_.height,
                       GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glc::check(gl, "Renderer: resolve");
}

void Renderer::render_environment(const Camera& camera) {
  draw_environment(camera);
  resolve();
}

void Renderer::render(const GpuDeformer& deformed, const Camera& camera, float floor_y, const Snow* snow) {
  if (deformed.vertex_count() != character_->vertex_count())
    throw std::invalid_argument("Renderer::render: the deformer holds " + std::to_string(deformed.vertex_count()) +
                                " vertices, the character " + std::to_string(character_->vertex_count()));
  const glc::GlApi& gl = context_->gl();
  const Effects& fx = settings_.effects;
  const float aspect = static_cast<float>(settings_.width) / static_cast<float>(settings_.height);
  const glm::mat4 view = camera.view();
  const glm::mat4 view_projection = camera.projection(aspect) * view;
  const glm::vec3 light = glm::normalize(glm::vec3(0.4f, 1.0f, 0.6f));
  const float figure = glm::length(camera.eye - camera.target);  // the framing distance, a size scale

  draw_environment(camera);

  // The floor, fading out at its edge.
  gl.glEnable(GL_DEPTH_TEST);
  gl.glDepthFunc(GL_LESS);
  gl.glEnable(GL_BLEND);
  gl.glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  floor_program_.use();
  gl.glUniformMatrix4fv(floor_program_.uniform("u_view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
  gl.glUniform3f(floor_program_.uniform("u_centre"), camera.target.x, floor_y, camera.target.z);
  gl.glUniform1f(floor_program_.uniform("u_extent"), 3.0f * figure);
  gl.glUniform1f(floor_program_.uniform("u_tile"), 0.25f * figure);
  gl.glUniform1i(floor_program_.uniform("u_environment"), fx.environment ? 1 : 0);
  gl.glUniform1i(floor_program_.uniform("u_toon"), fx.toon ? 1 : 0);
  floor_vao_.bind();
  gl.glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  gl.glDisable(GL_BLEND);

  // The character, from the deformer's buffer.
  character_vao_.bind();
  gl.glBindBuffer(GL_ARRAY_BUFFER, deformed.output().id());
  gl.glEnableVertexAttribArray(0);
  gl.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  gl.glEnableVertexAttribArray(1);
  gl.glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), glc::buffer_offset(3 * sizeof(float)));
  gl.glBindBuffer(GL_ARRAY_BUFFER, hair_attributes_.id());
  gl.glEnableVertexAttribArray(kHairAttribute);
  gl.glVertexAttribPointer(kHairAttribute, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec4), nullptr);
  gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
  auto character_uniforms = [&](const glc::Program& p, float push) {
    p.use();
    gl.glUniformMatrix4fv(p.uniform("u_view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
    gl.glUniform1f(p.uniform("u_push"), push);
    gl.glUniform1i(p.uniform("u_head_first"), static_cast<GLint>(character_->head_first));
  };
  const auto index_count = static_cast<GLsizei>(character_->mesh.indices.size());
  gl.glEnable(GL_CULL_FACE);
  gl.glCullFace(GL_BACK);
  character_uniforms(character_program_, 0.0f);
  gl.glUniform3fv(character_program_.uniform("u_eye"), 1, glm::value_ptr(camera.eye));
  gl.glUniform3fv(character_program_.uniform("u_light"), 1, glm::value_ptr(light));
  gl.glUniform1i(character_program_.uniform("u_toon"), fx.toon ? 1 : 0);
  gl.glUniform1i(character_program_.uniform("u_environment"), fx.environment ? 1 : 0);
  gl.glUniform1i(character_program_.uniform("u_cubemap"), 0);
  gl.glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);

  if (fx.toon) {
    // Outlines: the back faces, pushed out along the normals, drawn dark behind the surface.
    gl.glCullFace(GL_FRONT);
    character_uniforms(outline_program_, 0.004f * figure);
    gl.glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    gl.glCullFace(GL_BACK);
  }

  if (fx.hair && scalp_index_count_ > 0) {
    // Shells over the scalp, inside outwards, alpha-blended; depth tested, not written, so that the
    // shells do not hide each other.
    gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, scalp_indices_.id());
    gl.glEnable(GL_BLEND);
    gl.glDepthMask(GL_FALSE);
    gl.glDisable(GL_CULL_FACE);
    for (int s = 1; s <= kHairShells; ++s) {
      const float layer = static_cast<float>(s) / kHairShells;
      character_uniforms(hair_program_, layer * hair_length_);
      gl.glUniform3fv(hair_program_.uniform("u_light"), 1, glm::value_ptr(light));
      gl.glUniform1f(hair_program_.uniform("u_layer"), layer);
      gl.glUniform1f(hair_program_.uniform("u_strands"), kHairStrandsPerMetre);
      gl.glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(scalp_index_count_), GL_UNSIGNED_INT, nullptr);
    }
    gl.glDepthMask(GL_TRUE);
    gl.glDisable(GL_BLEND);
    gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
  }
  gl.glDisable(GL_CULL_FACE);

  if (fx.snow && snow != nullptr && !snow->flakes().empty()) {
    std::vector<glm::vec4>& flakes = snow_scratch_;
    flakes.clear();
    for (const Snow::Flake& f : snow->flakes()) flakes.emplace_back(f.position, f.size);
    gl.glBindBuffer(GL_ARRAY_BUFFER, snow_instances_.id());
    gl.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(flakes.size() * sizeof(glm::vec4)), flakes.data(),
                    GL_STREAM_DRAW);
    snow_vao_.bind();
    gl.glEnableVertexAttribArray(0);
    gl.glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(glm::vec4), nullptr);
    gl.glVertexAttribDivisor(0, 1);
    snow_program_.use();
    gl.glUniformMatrix4fv(snow_program_.uniform("u_view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
    // The camera's right and up in world space: the first two rows of the view rotation.
    const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
    gl.glUniform3fv(snow_program_.uniform("u_right"), 1, glm::value_ptr(right));
    gl.glUniform3fv(snow_program_.uniform("u_up"), 1, glm::value_ptr(up));
    gl.glEnable(GL_BLEND);
    gl.glDepthMask(GL_FALSE);
    gl.glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(flakes.size()));
    gl.glDepthMask(GL_TRUE);
    gl.glDisable(GL_BLEND);
  }
  // Resolve the samples.
  resolve();
}

void Renderer::read_rgb(std::span<std::uint8_t> out) const {
  const auto w = static_cast<std::size_t>(settings_.width), h = static_cast<std::size_t>(settings_.height);
  if (out.size() != w * h * 3)
    throw std::invalid_argument("Renderer::read_rgb: " + std::to_string(out.size()) + " bytes for a " +
                                std::to_string(w) + "x" + std::to_string(h) + " RGB frame");
  const glc::GlApi& gl = context_->gl();
  std::vector<std::uint8_t> rgba(w * h * 4);
  gl.glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_.id());
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.glReadPixels(0, 0, settings_.width, settings_.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glc::check(gl, "Renderer::read_rgb");
  for (std::size_t y = 0; y < h; ++y) {
    const std::uint8_t* src = rgba.data() + (h - 1 - y) * w * 4;  // GL's first row is the bottom
    std::uint8_t* dst = out.data() + y * w * 3;
    for (std::size_t x = 0; x < w; ++x) {
      dst[x * 3] = src[x * 4];
      dst[x * 3 + 1] = src[x * 4 + 1];
      dst[x * 3 + 2] = src[x * 4 + 2];
    }
  }
}

}  // namespace performer::render
