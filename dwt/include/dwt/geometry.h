#pragma once
#include <cstdint>
#include <vector>

namespace dwt {

// Where a plane's top-left sample sits on the JPEG 2000 reference grid. Only its parity matters to
// the transform itself, but the geometry keeps full coordinates for the codec.
struct Origin {
  std::int64_t x = 0;
  std::int64_t y = 0;
};

// A run of samples along one axis, with the reference-grid coordinate of its first sample.
struct AxisSpan {
  std::int64_t start = 0;
  int length = 0;

  int parity() const { return static_cast<int>(start & 1); }
  // Samples at even coordinates go low-pass: ceil(end/2) - ceil(start/2) of them (T.800 F.3.1).
  int low_count() const { return static_cast<int>(((start + length + 1) >> 1) - ((start + 1) >> 1)); }
  int high_count() const { return length - low_count(); }
  // The low-pass half, as the next level sees it: coordinates ceil(start/2) onward.
  AxisSpan low_half() const { return AxisSpan{(start + 1) >> 1, low_count()}; }
};

// The region one decomposition level transforms: the previous level's LL band, which in the
// in-place (Mallat) layout always sits at the top-left corner of the plane.
struct LevelGeometry {
  AxisSpan x;
  AxisSpan y;
};

enum class Orientation { LL = 0, HL = 1, LH = 2, HH = 3 };

// Rectangle of a band inside the Mallat layout of the plane (LL top-left, HL right of it, LH below,
// HH diagonal), in plane sample coordinates.
struct LayoutRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// Geometry of every level, finest first: entry d is the region transformed by level d + 1.
std::vector<LevelGeometry> decomposition(int width, int height, Origin origin, int levels);

// Number of levels after which the low-pass region is at most 1x1 (0 for a 1x1 plane).
int max_levels(int width, int height, Origin origin);

// Where band `o` of level `level` (1 = finest) lies in the Mallat layout. LL is only meaningful
// for the coarsest level.
LayoutRect band_rect(const std::vector<LevelGeometry>& levels, int level, Orientation o);

}  // namespace dwt
