// The procedural head's parameter grid and its triangles. Private to the library. Vertex 0 is the
// crown pole, then rows top to bottom of `columns` vertices each, then the bottom pole (the base of
// the neck). Rows are latitude angles theta (0 at +Y) from a density warp that crowds them onto the
// eyes and mouth, plus rows at the mouth line; columns are longitudes phi (0 toward +Z, positive
// toward +X), mirror-symmetric: column c and columns - c are at phi and -phi.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "head_landmarks.h"

namespace performer::detail {

inline constexpr int kNotSlit = std::numeric_limits<int>::min();

// Where a vertex sits in parameter space: what the shape and the poses are functions of.
struct HeadVertexParam {
  float theta = 0.0f;
  float phi = 0.0f;
  int slit = kNotSlit;  // -K..K on the mouth-line rows (negative above the line, 0 its bottom)
};

struct HeadGrid {
  std::vector<float> theta;  // per row
  std::vector<int> slit;     // per row, kNotSlit or -K..K
  std::vector<float> phi;    // per column
  float mouth_theta = 0.0f;  // the mouth line's latitude

  std::size_t rows() const { return theta.size(); }
  std::size_t columns() const { return phi.size(); }
  std::size_t vertex_count() const { return rows() * columns() + 2; }
  std::uint32_t vertex(std::size_t row, std::size_t column) const {
    return static_cast<std::uint32_t>(1 + row * columns() + column);
  }
  std::vector<HeadVertexParam> vertex_params() const;
  // Counter-clockwise seen from outside; quads split along mirror-image diagonals on the two sides
  // so the tessellation is as symmetric as the head.
  std::vector<std::uint32_t> triangles() const;
};

// rings, segments (even), mouth_rows and focus as in HeadParams, checked by the caller.
HeadGrid make_head_grid(const HeadLandmarks& marks, int rings, int segments, int mouth_rows, float focus);

}  // namespace performer::detail
