// Iso-surface extraction by marching cubes over a sampled grid (scalar_grid.h).
//
// The case tables are generated in code (marching_cubes_cases.h) from one rule per cube face, so
// neighbouring cubes always agree on a shared face: the result is a closed, consistently oriented
// 2-manifold wherever the surface stays away from the grid border, with no cracks at ambiguous
// faces.
#pragma once

#include "performer/scalar_grid.h"
#include "performer/triangle_mesh.h"

namespace performer {

// Triangles of the surface value == iso, with vertices on grid edges shared between the cubes that
// meet there (welded by construction). Samples below iso are inside; triangles wind counter-clockwise
// seen from the side where values are larger, so for a field that is negative inside a solid they
// face outward. A few cubes add one vertex at a polygon's centre (see marching_cubes_cases.h).
// Normals are left empty. Samples on the border should be outside for the surface to be closed.
TriangleMesh marching_cubes(const ScalarGrid& grid, float iso = 0.0f);

}  // namespace performer
