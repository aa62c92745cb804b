#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "codec/structure/grid.h"
#include "codec/structure/rect.h"
#include "dwt/geometry.h"

namespace codec {

// The standard's hierarchy (T.800 Annex B): tile > tile-component > resolution > subband, with the
// resolution also cut into precincts and each precinct's share of a subband into code-blocks. This
// is geometry only; coding results live beside it, indexed by CodeBlock::index.

// The subband orientations are the wavelet engine's own (LL, HL, LH, HH, as T.800 numbers them),
// so that geometry, quantisation and the DWT pass them to each other without conversions.
using BandOrientation = dwt::Orientation;

// log2 of a subband's nominal dynamic range gain (T.800 Table E.1, E.1.1.1): 0 for LL, 1 for HL
// and LH, 2 for HH. The quantiser's exponents and Mb count from it.
inline int band_gain(BandOrientation o) {
  switch (o) {
    case BandOrientation::LL:
      return 0;
    case BandOrientation::HH:
      return 2;
    default:
      return 1;
  }
}

// Per component coding style, as COD/COC state it.
struct CodingStyle {
  int levels = 5;        // NL, 0..32
  int xcb = 6, ycb = 6;  // code-block size exponents (2..10, xcb + ycb <= 12)
  // Precinct size exponents (PPx, PPy) per resolution 0..NL; empty means maximal (15, 15)
  // everywhere. A shorter list repeats its last entry for the finer resolutions.
  std::vector<std::pair<int, int>> precincts;

  bool explicit_precincts() const { return !precincts.empty(); }
  std::pair<int, int> precinct(int r) const;
};

struct CodeBlock {
  Rect rect;          // in subband coordinates
  std::size_t index;  // into the tile's per-code-block coding results
};

// The code-blocks of one precinct that lie in one subband, row-major cols x rows.
struct PrecinctBand {
  int band = 0;  // index into Resolution::bands
  int cols = 0, rows = 0;
  std::vector<CodeBlock> blocks;
};

struct Precinct {
  Rect rect;  // in resolution coordinates, clipped to the resolution
  std::vector<PrecinctBand> bands;
};

struct Subband {
  BandOrientation orientation = BandOrientation::LL;
  int level = 0;           // decomposition level nb (NL for LL)
  Rect rect;               // in subband coordinates (B-15)
  dwt::LayoutRect layout;  // where the DWT leaves it in the tile-component plane (Mallat layout)
  int xcb = 0, ycb = 0;    // effective code-block exponents, limited by the precinct size
};

struct Resolution {
  int r = 0;
  Rect rect;  // trx0.. (B-14)
  int ppx = 15, ppy = 15;
  int precincts_wide = 0, precincts_high = 0;
  std::vector<Subband> bands;  // LL for r = 0; HL, LH, HH otherwise
  std::vector<Precinct> precincts;
};

struct TileComponent {
  int component = 0;
  Rect rect;  // tcx0.. (B-12)
  int levels = 0;
  std::vector<Resolution> resolutions;  // r = 0..levels
};

struct Tile {
  int index = 0;
  Rect rect;
  std::vector<TileComponent> components;
  std::size_t code_blocks = 0;  // number of CodeBlock indices handed out
};

struct ComponentSampling {
  int dx = 1, dy = 1;  // XRsiz, YRsiz
};

// Builds tile `tile_index` of the grid for components with the given sampling and coding styles.
Tile build_tile(const ImageGrid& grid, const std::vector<ComponentSampling>& sampling,
                const std::vector<CodingStyle>& styles, int tile_index);

// Subband rectangle of orientation o at decomposition level nb of a tile-component (B-15).
Rect subband_rect(const Rect& tile_component, int nb, BandOrientation o);

}  // namespace codec
