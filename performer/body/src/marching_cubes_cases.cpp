#include "marching_cubes_cases.h"

#include <cmath>
#include <limits>

namespace performer::detail {

namespace {

int corner_of(int x, int y, int z) { return x | (y << 1) | (z << 2); }

int corner_coord(int corner, int axis) { return (corner >> axis) & 1; }

// The edge joining two corners that differ in exactly one coordinate.
int edge_between(int c0, int c1) {
  const int diff = c0 ^ c1;
  const int axis = diff == 1 ? 0 : diff == 2 ? 1 : 2;
  const int start = c0 & ~diff;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return axis * 4 + corner_coord(start, u) + 2 * corner_coord(start, v);
}

// Face f = 2 * axis + side; its corners counter-clockwise seen from outside. (u, v) = (a + 1, a + 2)
// is right-handed about +a, so the square's usual order goes round +a: right for side 1, reversed
// for side 0 whose outward normal is -a.
std::array<int, 4> face_corners(int face) {
  const int axis = face / 2, side = face % 2;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  static constexpr int kSquare[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::array<int, 4> corners{};
  for (int i = 0; i < 4; ++i) {
    const int k = side == 1 ? i : (4 - i) % 4;
    int coords[3];
    coords[axis] = side;
    coords[u] = kSquare[k][0];
    coords[v] = kSquare[k][1];
    corners[static_cast<std::size_t>(i)] = corner_of(coords[0], coords[1], coords[2]);
  }
  return corners;
}

// Bit f set when edge e lies on face f.
std::array<int, 12> edge_faces() {
  std::array<int, 12> faces{};
  for (int f = 0; f < 6; ++f) {
    const auto c = face_corners(f);
    for (int i = 0; i < 4; ++i) faces[static_cast<std::size_t>(edge_between(c[i], c[(i + 1) % 4]))] |= 1 << f;
  }
  return faces;
}

// Minimum-weight triangulation of the loop (weights: diagonal lengths between edge midpoints), using
// only diagonals between edges that share no face. Empty when there is none.
std::vector<std::array<std::uint8_t, 3>> triangulate(const std::vector<std::uint8_t>& loop,
                                                     const std::array<int, 12>& faces) {
  const int k = static_cast<int>(loop.size());
  if (k == 3) return {{0, 1, 2}};
  auto midpoint = [](int e, double out[3]) {
    const int start = edge_start_corner(e);
    for (int a = 0; a < 3; ++a) out[a] = corner_coord(start, a) + (a == edge_axis(e) ? 0.5 : 0.0);
  };
  constexpr double kNone = std::numeric_limits<double>::infinity();
  auto weight = [&](int i, int j) {                        // i < j, positions in the loop
    if (j == i + 1 || (i == 0 && j == k - 1)) return 0.0;  // a side of the polygon
    if (faces[loop[static_cast<std::size_t>(i)]] & faces[loop[static_cast<std::size_t>(j)]]) return kNone;
    double a[3], b[3];
    midpoint(loop[static_cast<std::size_t>(i)], a);
    midpoint(loop[static_cast<std::size_t>(j)], b);
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  };
  // cost[i][j]: best triangulation of the sub-polygon i..j (j - i >= 2); apex[i][j]: its third corner.
  std::vector<std::vector<double>> cost(static_cast<std::size_t>(k),
                                        std::vector<double>(static_cast<std::size_t>(k), 0.0));
  std::vector<std::vector<int>> apex(static_cast<std::size_t>(k), std::vector<int>(static_cast<std::size_t>(k), -1));
  for (int span = 2; span < k; ++span)
    for (int i = 0; i + span < k; ++i) {
      const int j = i + span;
      double best = kNone;
      for (int m = i + 1; m < j; ++m) {
        const double c = cost[static_cast<std::size_t>(i)][static_cast<std::size_t>(m)] +
                         cost[static_cast<std::size_t>(m)][static_cast<std::size_t>(j)] + weight(i, m) + weight(m, j);
        if (c < best) {
          best = c;
          apex[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = m;
        }
      }
      cost[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = best;
    }
  if (!std::isfinite(cost[0][static_cast<std::size_t>(k - 1)])) return {};
  std::vector<std::array<std::uint8_t, 3>> triangles;
  std::vector<std::array<int, 2>> todo{{0, k - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2) continue;
    const int m = apex[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    // i < m < j keeps the loop's winding.
    triangles.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(m), static_cast<std::uint8_t>(j)});
    todo.push_back({i, m});
    todo.push_back({m, j});
  }
  return triangles;
}

CubeCase build_case(int inside_mask, const std::array<int, 12>& faces) {
  auto inside = [inside_mask](int corner) { return ((inside_mask >> corner) & 1) != 0; };
  // next[e]: the segment leaving edge e's crossing on the face where the walk enters an inside
  // stretch across e ends at next[e], where the walk leaves it.
  std::array<int, 12> next;
  next.fill(-1);
  for (int f = 0; f < 6; ++f) {
    const auto c = face_corners(f);
    for (int i = 0; i < 4; ++i) {
      if (inside(c[i]) || !inside(c[(i + 1) % 4])) continue;  // not an entry
      int j = (i + 1) % 4;
      while (inside(c[(j + 1) % 4])) j = (j + 1) % 4;  // to the last inside corner of the stretch
      next[static_cast<std::size_t>(edge_between(c[i], c[(i + 1) % 4]))] = edge_between(c[j], c[(j + 1) % 4]);
    }
  }
  CubeCase result;
  std::array<bool, 12> used{};
  for (int start = 0; start < 12; ++start) {
    if (next[static_cast<std::size_t>(start)] < 0 || used[static_cast<std::size_t>(start)]) continue;
    CubeLoop loop;
    for (int e = start; !used[static_cast<std::size_t>(e)]; e = next[static_cast<std::size_t>(e)]) {
      used[static_cast<std::size_t>(e)] = true;
      loop.edges.push_back(static_cast<std::uint8_t>(e));
    }
    loop.triangles = triangulate(loop.edges, faces);
    result.loops.push_back(std::move(loop));
  }
  return result;
}

}  // namespace

int edge_start_corner(int e) {
  const int axis = edge_axis(e), rest = e % 4;
  int coords[3];
  coords[axis] = 0;
  coords[(axis + 1) % 3] = rest & 1;
  coords[(axis + 2) % 3] = rest >> 1;
  return corner_of(coords[0], coords[1], coords[2]);
}

const std::array<CubeCase, 256>& cube_cases() {
  static const std::array<CubeCase, 256> cases = [] {
    const std::array<int, 12> faces = edge_faces();
    std::array<CubeCase, 256> all;
    for (int mask = 0; mask < 256; ++mask) all[static_cast<std::size_t>(mask)] = build_case(mask, faces);
    return all;
  }();
  return cases;
}

}  // namespace performer::detail
