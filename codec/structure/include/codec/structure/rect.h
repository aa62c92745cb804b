#pragma once
#include <algorithm>
#include <cstdint>

namespace codec {

// A half-open rectangle [x0, x1) x [y0, y1) on some coordinate grid of T.800 Annex B: the reference
// grid, a tile-component, a resolution or a subband.
struct Rect {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  std::int64_t width() const { return x1 > x0 ? x1 - x0 : 0; }
  std::int64_t height() const { return y1 > y0 ? y1 - y0 : 0; }
  bool empty() const { return width() == 0 || height() == 0; }
  Rect intersect(const Rect& o) const {
    return Rect{std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  bool operator==(const Rect&) const = default;
};

// Non-negative operands only: every coordinate of T.800's grids is unsigned.
inline std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return (a + b - 1) / b; }
inline std::int64_t ceil_shift(std::int64_t a, int e) { return (a + (std::int64_t{1} << e) - 1) >> e; }
inline std::int64_t floor_shift(std::int64_t a, int e) { return a >> e; }

}  // namespace codec
