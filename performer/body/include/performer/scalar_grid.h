// A scalar function sampled on a regular 3D grid: the input of iso-surface extraction
// (marching_cubes.h). Samples sit at origin + cell * (i, j, k).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace performer {

struct ScalarGrid {
  int nx = 0, ny = 0, nz = 0;  // samples per axis
  glm::vec3 origin{0.0f};      // position of sample (0, 0, 0)
  float cell = 1.0f;           // spacing between neighbouring samples
  std::vector<float> values;   // x fastest, then y, then z: index (k * ny + j) * nx + i

  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(i);
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  glm::vec3 position(int i, int j, int k) const {
    return origin + cell * glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k));
  }
};

// Samples f on the smallest grid of spacing `cell` that covers the box [lo, hi], centred on it.
// Slabs of constant z go to up to `threads` threads (0: hardware concurrency); f must be safe to
// call concurrently. Throws std::invalid_argument for a non-positive cell, an empty box, or a grid
// of more than 2^31 samples.
ScalarGrid sample_grid(const glm::vec3& lo, const glm::vec3& hi, float cell,
                       const std::function<float(const glm::vec3&)>& f, unsigned threads = 0);

}  // namespace performer
