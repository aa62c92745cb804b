#include "codec/structure/grid.h"

#include <string>

#include "codec/structure/error.h"

namespace codec {

Rect ImageGrid::tile_rect(int t) const {
  const int p = t % tiles_wide(), q = t / tiles_wide();
  return Rect{std::max(tile_x0 + p * tile_width, image.x0), std::max(tile_y0 + q * tile_height, image.y0),
              std::min(tile_x0 + (p + 1) * tile_width, image.x1), std::min(tile_y0 + (q + 1) * tile_height, image.y1)};
}

void validate(const ImageGrid& g) {
  constexpr std::int64_t kMax = 0xFFFFFFFFll;
  auto fail = [](const std::string& why) { throw EncodeError(why); };
  if (g.image.x0 < 0 || g.image.y0 < 0 || g.tile_x0 < 0 || g.tile_y0 < 0) fail("offsets must be non-negative");
  if (g.image.x1 > kMax || g.image.y1 > kMax) fail("the image extends past the 32-bit reference grid");
  if (g.image.x1 <= g.image.x0 || g.image.y1 <= g.image.y0) fail("the image is empty");
  if (g.tile_width <= 0 || g.tile_height <= 0 || g.tile_width > kMax || g.tile_height > kMax)
    fail("tile sizes must be between 1 and 2^32-1");
  if (g.tile_x0 > g.image.x0 || g.tile_y0 > g.image.y0)
    fail("the tile origin (" + std::to_string(g.tile_x0) + "," + std::to_string(g.tile_y0) +
         ") must not lie beyond the image origin (" + std::to_string(g.image.x0) + "," + std::to_string(g.image.y0) +
         ") (T.800 A.5.1: XTOsiz <= XOsiz, YTOsiz <= YOsiz)");
  if (g.tile_x0 + g.tile_width <= g.image.x0 || g.tile_y0 + g.tile_height <= g.image.y0)
    fail("the first tile does not reach the image area (T.800 A.5.1: XTsiz + XTOsiz > XOsiz)");
  if (static_cast<std::int64_t>(g.tiles_wide()) * g.tiles_high() > 65535)
    fail("the tiling makes " + std::to_string(static_cast<std::int64_t>(g.tiles_wide()) * g.tiles_high()) +
         " tiles; a codestream holds at most 65535");
}

Rect tile_component_rect(const Rect& t, int dx, int dy) {
  return Rect{ceil_div(t.x0, dx), ceil_div(t.y0, dy), ceil_div(t.x1, dx), ceil_div(t.y1, dy)};
}

}  // namespace codec
