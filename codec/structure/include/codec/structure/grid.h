#pragma once
#include <cstdint>
#include <vector>

#include "codec/structure/rect.h"

namespace codec {

// The reference grid and its tiling, as the SIZ marker states them (T.800 A.5.1, B.2, B.3).
struct ImageGrid {
  Rect image;                    // (XOsiz, YOsiz) .. (Xsiz, Ysiz)
  std::int64_t tile_width = 0;   // XTsiz
  std::int64_t tile_height = 0;  // YTsiz
  std::int64_t tile_x0 = 0;      // XTOsiz
  std::int64_t tile_y0 = 0;      // YTOsiz

  int tiles_wide() const { return static_cast<int>(ceil_div(image.x1 - tile_x0, tile_width)); }
  int tiles_high() const { return static_cast<int>(ceil_div(image.y1 - tile_y0, tile_height)); }
  int tile_count() const { return tiles_wide() * tiles_high(); }
  // Tile t's area on the reference grid, clipped to the image (B-7..B-10).
  Rect tile_rect(int t) const;
};

// Throws codec::EncodeError naming the violated SIZ constraint (T.800 A.5.1): the image offset
// inside the image, the first tile touching the image area, sizes within 32 bits.
void validate(const ImageGrid& grid);

// A tile-component's area: the tile on the grid of a component subsampled by (dx, dy) (B-12).
Rect tile_component_rect(const Rect& tile, int dx, int dy);

}  // namespace codec
