#include "performer/marching_cubes.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "marching_cubes_cases.h"

namespace performer {

namespace {

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// Vertices are keyed by the grid edge they sit on. Only two z layers of x/y edges and one layer of
// z edges are live at a time, so the maps cost O(nx * ny) however deep the grid.
class EdgeVertices {
 public:
  EdgeVertices(const ScalarGrid& grid, float iso, TriangleMesh& mesh)
      : grid_(grid),
        iso_(iso),
        mesh_(mesh),
        layer_size_(static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny)) {
    for (auto& layer : xy_) layer.assign(2 * layer_size_, kNoVertex);
    z_.assign(layer_size_, kNoVertex);
  }

  // Moves to the next slab of cubes: layer k + 1 becomes layer k.
  void advance() {
    std::swap(xy_[0], xy_[1]);
    std::fill(xy_[1].begin(), xy_[1].end(), kNoVertex);
    std::fill(z_.begin(), z_.end(), kNoVertex);
  }

  // The vertex on the edge from sample (i, j, k) along `axis`, where k is the slab's lower layer
  // plus dz (0 or 1).
  std::uint32_t get(int i, int j, int k, int dz, int axis) {
    const std::size_t column =
        static_cast<std::size_t>(j) * static_cast<std::size_t>(grid_.nx) + static_cast<std::size_t>(i);
    std::uint32_t& slot = axis == 2 ? z_[column] : xy_[dz][2 * column + static_cast<std::size_t>(axis)];
    if (slot == kNoVertex) slot = make(i, j, k + dz, axis);
    return slot;
  }

 private:
  std::uint32_t make(int i, int j, int k, int axis) {
    const int i1 = i + (axis == 0), j1 = j + (axis == 1), k1 = k + (axis == 2);
    const float v0 = grid_.at(i, j, k), v1 = grid_.at(i1, j1, k1);
    // One end is below iso and one is not, so v0 != v1. The clamp keeps a vertex off the sample
    // itself when a sample equals iso exactly: otherwise several edges would put vertices on the
    // same point and leave zero-area triangles.
    const float t = std::clamp((iso_ - v0) / (v1 - v0), 1e-3f, 1.0f - 1e-3f);
    const glm::vec3 p0 = grid_.position(i, j, k), p1 = grid_.position(i1, j1, k1);
    if (mesh_.positions.size() >= kNoVertex) throw std::length_error("marching_cubes: more than 2^32 - 1 vertices");
    mesh_.positions.push_back(p0 + t * (p1 - p0));
    return static_cast<std::uint32_t>(mesh_.positions.size() - 1);
  }

  const ScalarGrid& grid_;
  float iso_;
  TriangleMesh& mesh_;
  std::size_t layer_size_;
  std::array<std::vector<std::uint32_t>, 2> xy_;  // [layer][column * 2 + axis]
  std::vector<std::uint32_t> z_;                  // [column]
};

}  // namespace

TriangleMesh marching_cubes(const ScalarGrid& grid, float iso) {
  if (grid.nx < 0 || grid.ny < 0 || grid.nz < 0 ||
      grid.values.size() !=
          static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) * static_cast<std::size_t>(grid.nz))
    throw std::invalid_argument("marching_cubes: grid holds " + std::to_string(grid.values.size()) + " values for " +
                                std::to_string(grid.nx) + "x" + std::to_string(grid.ny) + "x" +
                                std::to_string(grid.nz) + " samples");
  TriangleMesh mesh;
  if (grid.nx < 2 || grid.ny < 2 || grid.nz < 2) return mesh;
  const auto& cases = detail::cube_cases();
  std::array<std::array<int, 3>, 12> edge_start{};  // corner offsets of each edge's start
  for (int e = 0; e < 12; ++e) {
    const int c = detail::edge_start_corner(e);
    edge_start[static_cast<std::size_t>(e)] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
  }
  EdgeVertices vertices(grid, iso, mesh);
  std::array<std::uint32_t, 12> ids{};
  for (int k = 0; k + 1 < grid.nz; ++k) {
    for (int j = 0; j + 1 < grid.ny; ++j)
      for (int i = 0; i + 1 < grid.nx; ++i) {
        int mask = 0;
        for (int c = 0; c < 8; ++c)
          if (grid.at(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)) < iso) mask |= 1 << c;
        if (mask == 0 || mask == 255) continue;
        for (const detail::CubeLoop& loop : cases[static_cast<std::size_t>(mask)].loops) {
          for (std::size_t n = 0; n < loop.edges.size(); ++n) {
            const int e = loop.edges[n];
            const auto& s = edge_start[static_cast<std::size_t>(e)];
            ids[n] = vertices.get(i + s[0], j + s[1], k, s[2], detail::edge_axis(e));
          }
          if (!loop.triangles.empty()) {
            for (const auto& t : loop.triangles)
              for (const std::uint8_t corner : t) mesh.indices.push_back(ids[corner]);
            continue;
          }
          // No triangulation keeps clear of the cube's faces: fan around the loop's centre.
          glm::vec3 centre(0.0f);
          for (std::size_t n = 0; n < loop.edges.size(); ++n) centre += mesh.positions[ids[n]];
          mesh.positions.push_back(centre / static_cast<float>(loop.edges.size()));
          const auto middle = static_cast<std::uint32_t>(mesh.positions.size() - 1);
          for (std::size_t n = 0; n < loop.edges.size(); ++n)
            mesh.indices.insert(mesh.indices.end(), {middle, ids[n], ids[(n + 1) % loop.edges.size()]});
        }
      }
    vertices.advance();
  }
  return mesh;
}

}  // namespace performer
