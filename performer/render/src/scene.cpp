#include "performer/render/scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace performer::render {

Effects parse_effects(std::string_view list) {
  Effects e;
  if (list.empty() || list == "none") return e;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    if (name == "env" || name == "environment")
      e.environment = true;
    else if (name == "hair")
      e.hair = true;
    else if (name == "snow")
      e.snow = true;
    else if (name == "toon")
      e.toon = true;
    else
      throw std::invalid_argument("unknown effect \"" + std::string(name) + "\" (known: env, hair, snow, toon)");
    start = comma + 1;
  }
  return e;
}

std::string effects_name(const Effects& e) {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += ',';
    s += name;
  };
  add(e.environment, "env");
  add(e.hair, "hair");
  add(e.snow, "snow");
  add(e.toon, "toon");
  return s.empty() ? "none" : s;
}

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)); }

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(vertical_fov, aspect, near_plane, far_plane);
}

Camera frame_figure(const glm::vec3& hips, float floor_y, float height, const glm::vec3& facing, float aspect) {
  Camera c;
  glm::vec3 front(facing.x, 0.0f, facing.z);
  front = glm::length(front) > 1e-6f ? glm::normalize(front) : glm::vec3(0.0f, 0.0f, 1.0f);
  const glm::vec3 side = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), front));
  const float middle = floor_y + 0.5f * height;
  c.target = glm::vec3(hips.x, middle, hips.z);
  // Distance at which `height` fills 80 % of the vertical field of view (and of a narrow frame's
  // horizontal one).
  const float half = 0.5f * height / 0.8f;
  const float fit = std::max(half / std::tan(0.5f * c.vertical_fov), half / (std::tan(0.5f * c.vertical_fov) * aspect));
  const glm::vec3 from = glm::normalize(front * 0.87f + side * 0.5f + glm::vec3(0.0f, 0.12f, 0.0f));
  c.eye = c.target + from * fit;
  c.near_plane = 0.02f * fit;
  c.far_plane = 60.0f * fit;
  return c;
}

Snow::Snow(std::size_t count, const glm::vec3& centre, float extent, float floor_y, float height, std::uint32_t seed)
    : flakes_(count), centre_(centre), extent_(extent), floor_y_(floor_y), height_(height), rng_(seed) {
  for (Flake& f : flakes_) respawn(f, true);
}

void Snow::respawn(Flake& f, bool anywhere) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  f.position = centre_ + glm::vec3((2.0f * unit(rng_) - 1.0f) * extent_, 0.0f, (2.0f * unit(rng_) - 1.0f) * extent_);
  f.position.y = floor_y_ + (anywhere ? unit(rng_) : 1.0f) * height_;
  f.velocity = glm::vec3(0.0f, -0.1f * height_, 0.0f);
  f.size = (0.004f + 0.006f * unit(rng_)) * height_;
}

void Snow::step(float dt) {
  time_ += dt;
  // A slowly turning wind, and air drag pulling each flake's velocity towards it; small flakes
  // settle to a terminal fall of about a tenth of the box height per second.
  const glm::vec3 wind(0.06f * height_ * std::sin(0.4f * time_), -0.12f * height_,
                       0.04f * height_ * std::cos(0.3f * time_));
  const float drag = 1.6f;
  for (Flake& f : flakes_) {
    const glm::vec3 acceleration = drag * (wind - f.velocity);
    f.velocity += acceleration * dt;  // Euler: velocity, then position with the new velocity
    f.position += f.velocity * dt;
    if (f.position.y < floor_y_) respawn(f, false);
    // Keep the box around the (moving) centre: wrap horizontally.
    for (int axis : {0, 2}) {
      const float d = f.position[axis] - centre_[axis];
      if (d > extent_) f.position[axis] -= 2.0f * extent_;
      if (d < -extent_) f.position[axis] += 2.0f * extent_;
    }
  }
}

}  // namespace performer::render
