// The 256 marching-cubes cases, built in code rather than copied from a table.
//
// Corner c of a cube sits at (c & 1, c >> 1 & 1, c >> 2 & 1). Edge e runs along axis a = e / 4 from
// the corner whose other two coordinates (axes a + 1 and a + 2, mod 3) are the bits of e % 4.
// A case is the set of corners inside (below the iso value), bit c for corner c.
//
// Construction: on every face, each stretch of inside corners is cut off by a segment from the edge
// where the walk (counter-clockwise seen from outside the cube) enters the stretch to the edge where
// it leaves; on a face with two inside corners diagonally opposite, each is cut off on its own. The
// segments chain into closed loops, one per surface piece, each oriented counter-clockwise around
// the outward (towards larger values) normal. A loop is triangulated with diagonals only between
// edges that share no cube face: a diagonal between two edges of one face could be made by the
// neighbouring cube too and end up in four triangles. A loop with no such triangulation is fanned
// around an extra vertex at its centre instead. Either way every mesh edge lies in exactly two
// triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace performer::detail {

struct CubeLoop {
  std::vector<std::uint8_t> edges;                     // the loop, in order
  std::vector<std::array<std::uint8_t, 3>> triangles;  // indices into edges; empty: fan around the centre
};

struct CubeCase {
  std::vector<CubeLoop> loops;
};

// start corner and axis of edge e
inline int edge_axis(int e) { return e / 4; }
int edge_start_corner(int e);

// All 256 cases, built on first use.
const std::array<CubeCase, 256>& cube_cases();

}  // namespace performer::detail
