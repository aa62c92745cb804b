// Wavelet-domain geometric deformation (thesis 4.7.1, Figure 4.9): a surface's grid of 3D control
// points is three float planes (x, y, z); scaling their subbands reshapes the surface at the scale
// each band stands for, and the inverse transform gives the deformed net.
//
// Control-net text format (".net" or ".txt"): '#' starts a comment; the first other line is
//   controlnet ROWS COLUMNS [wrap] [capped]
// ("wrap": the last column joins the first, as around a head; "capped": the first and the last row
// are closed by a fan, as at a head's crown and neck), then ROWS * COLUMNS lines "x y z", row by
// row. PLY grids: an ASCII PLY whose header has "comment grid ROWS COLUMNS [wrap] [capped]" and a
// vertex element whose first three properties are x y z (float or double), ROWS * COLUMNS vertices
// row by row; faces are ignored on reading (write_control_net_ply writes the grid's quads).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "dwt/params.h"
#include "wavelet_apps/band_spec.h"
#include "wavelet_apps/engine.h"

namespace wavelet_apps {

using Point3 = std::array<float, 3>;

struct ControlNet {
  int rows = 0;
  int columns = 0;
  bool wrap = false;           // column columns-1 joins column 0
  bool capped = false;         // first and last rows closed by fans around their centroids
  std::vector<Point3> points;  // rows * columns, row-major

  const Point3& at(int row, int column) const {
    return points[static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(column)];
  }
};

// Throws AppError naming the file and line for anything malformed.
ControlNet read_control_net(const std::filesystem::path& path);
void write_control_net_text(const std::filesystem::path& path, const ControlNet& net);  // atomic
void write_control_net_ply(const std::filesystem::path& path, const ControlNet& net);   // atomic

// The channel names of band specs for nets: X, Y, Z.
std::vector<std::string> axis_names();

// Every axis plane forward-transformed, scaled per band (the last matching spec; default 1), and
// inverse-transformed. The level count is checked against the net's size (dwt::validate).
ControlNet deform_net(const ControlNet& net, const dwt::DwtParams& params, std::span<const ScaleSpec> bands,
                      WaveletEngine& engine);

// A triangle mesh: three indices per triangle, counter-clockwise seen from outside for nets whose
// rows run top to bottom and columns left to right seen from outside.
struct SurfaceMesh {
  std::vector<Point3> positions;
  std::vector<std::uint32_t> indices;
};

// The surface the net controls: with `subdivisions` 1 the net's own quads, each split in two
// triangles; with more, a uniform bicubic B-spline surface evaluated `subdivisions` times per net
// cell (clamped at open ends, periodic across a wrap), so the surface is smooth. Caps add one
// centre vertex per capped end.
SurfaceMesh tessellate(const ControlNet& net, int subdivisions);

// OBJ or PLY by extension (".obj", ".ply"); atomic. AppError for other extensions.
void write_mesh(const std::filesystem::path& path, const SurfaceMesh& mesh);

// Checks what a viewer needs: index count a multiple of 3, indices in range, no triangle with a
// repeated vertex, finite coordinates. Returns an empty string when valid, else the problem.
std::string mesh_problem(const SurfaceMesh& mesh);

// The performer's procedural head (performer/procedural_head.h) as a net: its latitude-longitude
// grid, columns wrapping around, rows from crown to neck, the poles left to the caps, the seam at
// the back of the head. `rings` and `segments` as in performer::HeadParams.
ControlNet head_control_net(int rings = 30, int segments = 48);

}  // namespace wavelet_apps
