// Sharp edges, the hard case for a wavelet codec (ringing, large high-pass
// coefficients). Three horizontal bands, top to bottom:
//   1. eight vertical stripes at levels chosen so the steps between them have
//      many different heights;
//   2. checkerboards whose cell size changes across the image (1, 2, 3, 5, 8
//      and 13 pixels, so some cells straddle dyadic boundaries and some don't);
//   3. a diagonal edge from the band's top-left to its bottom-right corner,
//      at whatever angle the band's aspect ratio gives (rarely 45 degrees).

#include <array>

#include "canvas.h"
#include "level_math.h"

namespace testimages::detail {
namespace {

// First row of band b when the height is split into three.
int band_start(int band, int height) { return (band * height + 2) / 3; }

std::uint32_t stripes(const Canvas& canvas, int x) {
  // Levels in eighths of the range.
  static constexpr std::array<std::uint32_t, 8> kEighths = {0, 8, 2, 6, 3, 5, 1, 7};
  const int stripe = int(std::int64_t(x) * 8 / canvas.width);
  return lerp_level(0, canvas.max_level, kEighths[std::size_t(stripe)], 8);
}

std::uint32_t checkerboards(const Canvas& canvas, int x, int band_y) {
  static constexpr std::array<int, 6> kCellSizes = {1, 2, 3, 5, 8, 13};
  const int segment = int(std::int64_t(x) * 6 / canvas.width);
  const int cell = kCellSizes[std::size_t(segment)];
  return ((x / cell + band_y / cell) & 1) ? canvas.max_level : 0;
}

std::uint32_t diagonal(const Canvas& canvas, int x, int band_y, int band_height) {
  // Above the line from (0, 0) to (width, band_height): bright.
  return std::int64_t(x) * band_height > std::int64_t(band_y) * canvas.width ? canvas.max_level : 0;
}

}  // namespace

std::uint32_t edges_level(const Canvas& canvas, int x, int y, int c) {
  const int band = int(std::int64_t(y) * 3 / canvas.height);
  const int band_y = y - band_start(band, canvas.height);
  std::uint32_t level = 0;
  switch (band) {
    case 0:
      level = stripes(canvas, x);
      break;
    case 1:
      level = checkerboards(canvas, x, band_y);
      break;
    default:
      level = diagonal(canvas, x, band_y, band_start(3, canvas.height) - band_start(2, canvas.height));
  }
  return channel_variant(level, canvas.max_level, c);
}

}  // namespace testimages::detail
