// What the renderer draws besides the character (thesis 3.7): effects, camera and the snow
// particle system. Plain data and small functions; the GL side is renderer.h.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace performer::render {

// Section 3.7's effects, each optional.
struct Effects {
  bool environment = false;  // a sphere around the scene shaded from the cube map by the view vector
  bool hair = false;         // alpha-blended shells on the scalp
  bool snow = false;         // Euler-integrated particles drawn as camera-facing billboards
  bool toon = false;         // cartoon shading: quantised light and dark outlines
};

// "env,hair,snow,toon" (any subset, any order; "none" or empty for none). Throws
// std::invalid_argument naming an unknown effect and the known ones.
Effects parse_effects(std::string_view list);
std::string effects_name(const Effects& effects);  // the same list back, "none" when empty

struct Camera {
  glm::vec3 eye{0.0f, 1.0f, 3.0f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  float vertical_fov = 0.7f;  // radians
  float near_plane = 0.05f, far_plane = 100.0f;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

// A camera that frames a standing figure of height `height` whose hips are at `hips` (the floor at
// floor_y): from the front-left, slightly above, the whole body in about 80 % of the frame height.
// `facing`: the direction the figure faces, horizontal.
Camera frame_figure(const glm::vec3& hips, float floor_y, float height, const glm::vec3& facing, float aspect);

// Snow (thesis 3.7: a particle system integrated with Euler's method every frame, drawn as
// billboards facing the camera). Flakes fall through a box around a centre, drift with a wind that
// varies in time, and start again at the top when they reach the floor.
class Snow {
 public:
  struct Flake {
    glm::vec3 position;
    glm::vec3 velocity;
    float size;
  };
  // `count` flakes in a box of half-width `extent` from floor_y up to floor_y + height.
  Snow(std::size_t count, const glm::vec3& centre, float extent, float floor_y, float height, std::uint32_t seed = 1);
  // One Euler step of dt seconds: v += (gravity + drag towards the wind) dt, x += v dt.
  void step(float dt);
  void recentre(const glm::vec3& centre) { centre_ = centre; }
  std::span<const Flake> flakes() const { return flakes_; }

 private:
  void respawn(Flake& flake, bool anywhere);
  std::vector<Flake> flakes_;
  glm::vec3 centre_;
  float extent_, floor_y_, height_;
  float time_ = 0.0f;
  std::mt19937 rng_;
};

}  // namespace performer::render
