// The character's rendering (thesis 3.7) on the shared GL layer: per-pixel lighting of the
// deformed character, a floor, and the optional effects of scene.h (an environment sphere from a
// cube map, hair shells, snow billboards, cartoon shading with outlines), into an offscreen
// multisampled framebuffer with depth, resolved and read back as RGB for images and video.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "glcontext/context.h"
#include "glcontext/resources.h"
#include "performer/character.h"
#include "performer/render/gpu_deformer.h"
#include "performer/render/scene.h"

namespace performer::render {

struct RenderSettings {
  int width = 640;
  int height = 480;
  int samples = 4;  // multisampling; clamped to what the driver offers
  Effects effects;
  // posx, negx, posy, negy, posz, negz (.jpg, .png or .ppm) for the environment effect.
  std::filesystem::path cubemap_dir;
};

// The file of cube map face `face` ("posx", ...) in `dir`: the first of .jpg, .png and .ppm there
// (PPM conversions serve where OpenImageIO, which reads JPEG and PNG, is absent); empty if none.
std::filesystem::path cubemap_face_file(const std::filesystem::path& dir, const std::string& face);

class Renderer {
 public:
  // `character` is what `deformed` deforms; both must outlive the renderer, and `context` be
  // current. Throws std::invalid_argument for a bad size or a missing cube map face (naming the
  // file), glc::GlError for GL failures.
  Renderer(glc::Context& context, const Character& character, const RenderSettings& settings);

  // Draws one frame of the deformer's current result seen by `camera`, the floor at floor_y (the
  // character's lowest rest point), snow when the effect is on and `snow` is given.
  void render(const GpuDeformer& deformed, const Camera& camera, float floor_y, const Snow* snow = nullptr);

  // The environment (or sky) alone seen by `camera`: what render() draws behind everything.
  void render_environment(const Camera& camera);

  // The last frame as 8-bit RGB, rows top first: width * height * 3 bytes.
  void read_rgb(std::span<std::uint8_t> out) const;

  int width() const { return settings_.width; }
  int height() const { return settings_.height; }
  int samples() const { return samples_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  void draw_environment(const Camera& camera);  // binds the scene target, clears, draws the sky
  void resolve();                               // the samples into the read-back target

  glc::Context* context_;
  const Character* character_;
  RenderSettings settings_;
  int samples_ = 0;
  std::size_t scalp_index_count_ = 0;    // the triangles the hair shells are drawn over
  float hair_length_ = 0.0f;             // the outermost shell's distance from the scalp
  std::vector<glm::vec4> snow_scratch_;  // each frame's flakes on their way to the GPU
  glc::Renderbuffer color_, depth_, resolved_;
  glc::Framebuffer scene_fbo_, resolve_fbo_;
  glc::Program character_program_, outline_program_, hair_program_, sky_program_, floor_program_, snow_program_;
  glc::Buffer indices_, scalp_indices_, hair_attributes_, snow_instances_, floor_corners_;
  glc::VertexArray character_vao_, sky_vao_, floor_vao_, snow_vao_;
  glc::Texture cubemap_;
};

}  // namespace performer::render
