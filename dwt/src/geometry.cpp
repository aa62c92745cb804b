#include "dwt/geometry.h"

#include "dwt/error.h"

namespace dwt {

std::vector<LevelGeometry> decomposition(int width, int height, Origin origin, int levels) {
  std::vector<LevelGeometry> out;
  out.reserve(static_cast<std::size_t>(levels > 0 ? levels : 0));
  LevelGeometry g{AxisSpan{origin.x, width}, AxisSpan{origin.y, height}};
  for (int d = 0; d < levels; ++d) {
    out.push_back(g);
    g = LevelGeometry{g.x.low_half(), g.y.low_half()};
  }
  return out;
}

int max_levels(int width, int height, Origin origin) {
  AxisSpan x{origin.x, width}, y{origin.y, height};
  int levels = 0;
  while (x.length > 1 || y.length > 1) {
    x = x.low_half();
    y = y.low_half();
    ++levels;
  }
  return levels;
}

LayoutRect band_rect(const std::vector<LevelGeometry>& levels, int level, Orientation o) {
  if (level < 1 || level > static_cast<int>(levels.size())) throw DwtError("band_rect: level out of range");
  const LevelGeometry& g = levels[static_cast<std::size_t>(level - 1)];
  const int lx = g.x.low_count(), ly = g.y.low_count();
  switch (o) {
    case Orientation::LL:
      return {0, 0, lx, ly};
    case Orientation::HL:
      return {lx, 0, g.x.length - lx, ly};
    case Orientation::LH:
      return {0, ly, lx, g.y.length - ly};
    case Orientation::HH:
      return {lx, ly, g.x.length - lx, g.y.length - ly};
  }
  return {};
}

}  // namespace dwt
