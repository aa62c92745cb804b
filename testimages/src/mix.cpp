// A busy, natural-ish image made of the other patterns, one per quadrant:
//   top-left: zone plate       top-right: edges
//   bottom-left: diagonal ramp with a little grain (like a photographed sky)
//   bottom-right: noise
// Each quadrant is a complete small pattern drawn in its own coordinates.

#include "canvas.h"

namespace testimages::detail {

std::uint32_t mix_level(const Canvas& canvas, int x, int y, int c) {
  // The left and top quadrants take the extra pixel of odd sizes; on a
  // one-pixel-wide or -high image the other quadrants are simply empty.
  const int left_width = (canvas.width + 1) / 2;
  const int top_height = (canvas.height + 1) / 2;
  const bool right = x >= left_width;
  const bool bottom = y >= top_height;

  Canvas quadrant = canvas;
  quadrant.width = right ? canvas.width - left_width : left_width;
  quadrant.height = bottom ? canvas.height - top_height : top_height;
  const int qx = right ? x - left_width : x;
  const int qy = bottom ? y - top_height : y;

  if (!bottom) {
    return right ? edges_level(quadrant, qx, qy, c) : zoneplate_level(quadrant, qx, qy, c);
  }
  if (right) return noise_level(quadrant, qx, qy, c);
  // 7/8 ramp + 1/8 noise stays within 0..max_level.
  const std::uint64_t ramp = gradient_diag_level(quadrant, qx, qy, c);
  const std::uint64_t grain = noise_level(quadrant, qx, qy, c);
  return std::uint32_t((7 * ramp + grain + 4) / 8);
}

}  // namespace testimages::detail
