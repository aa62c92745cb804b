#pragma once
#include <cstdint>
#include <vector>

namespace codec::t2 {

// Progression orders of T.800 B.12 (COD's SGcod / POC values 0..4, in that order).
enum class Order { LRCP, RLCP, RPCL, PCRL, CPRL };

struct ResolutionGeometry {
  std::int64_t x0, y0, x1, y1;  // resolution rectangle (trx0, try0, trx1, try1), that resolution's coordinates
  int ppx, ppy;                 // precinct size exponents PPx, PPy
  int precincts_wide, precincts_high;
};

struct ComponentGeometry {
  int dx = 1, dy = 1;                           // XRsiz, YRsiz
  std::vector<ResolutionGeometry> resolutions;  // index r = 0..NL (NL may differ per component: COC)
};

struct PacketId {
  int layer, resolution, component, precinct;  // precinct: raster index within (component, resolution)
  friend bool operator==(const PacketId&, const PacketId&) = default;
};

// The packets of one tile, in the order `order` puts them (B.12.1). Tile coordinates are on the
// reference grid ([tile_x0, tile_x1) x [tile_y0, tile_y1), non-negative). Every (layer, r, c, p)
// with r <= NL(c) and p < precincts_wide * precincts_high appears exactly once.
// The position-driven orders (RPCL, PCRL, CPRL) follow B.12.1.3-5 literally: a precinct is
// visited at the first reference-grid point (x, y) of the tile, in raster order, where
//   (y divisible by YRsiz * 2^(PPy + NL - r)  or  y == ty0 and try0 is not on a precinct boundary)
//   and the same for x,
// and is identified by its position (B-20). So components with different sampling and
// resolutions with different precinct sizes interleave by where their precincts begin on the grid.
// Throws std::invalid_argument for geometry that cannot be consistent (e.g. precinct counts the
// tile's area cannot produce).
std::vector<PacketId> progression(Order order, int layers, std::int64_t tile_x0, std::int64_t tile_y0,
                                  std::int64_t tile_x1, std::int64_t tile_y1,
                                  const std::vector<ComponentGeometry>& components);

}  // namespace codec::t2
