// Taubin's lambda|mu smoothing (G. Taubin, "A signal processing approach to fair surface design",
// SIGGRAPH 1995): removes the terracing marching cubes leaves without shrinking the mesh the way
// repeated Laplacian averaging does. Each iteration moves every vertex towards the average of its
// neighbours by lambda, then away from it by -mu (mu < -lambda < 0), which damps the high
// frequencies (steps, stairs) and passes the low ones (the overall shape).
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace performer {

struct TaubinParams {
  int iterations = 10;  // lambda-then-mu pairs
  float lambda = 0.5f;  // in (0, 1)
  float mu = -0.53f;    // negative, |mu| slightly above lambda
};

// Smooths positions in place; neighbours are the vertices sharing an edge of a triangle in
// `indices`. Vertices in no triangle stay put. Threads over vertex ranges (0: hardware concurrency).
// Throws std::invalid_argument on an index out of range, an index count not a multiple of 3, or
// parameters outside the ranges above.
void taubin_smooth(std::span<glm::vec3> positions, std::span<const std::uint32_t> indices, const TaubinParams& params,
                   unsigned threads = 0);

}  // namespace performer
