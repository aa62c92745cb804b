// Zone plate: cos(k r^2) around the image centre. Its local frequency grows
// linearly with the radius and reaches Nyquist (half a cycle per pixel) at
// the middle of the longer edge, so one image covers every frequency and
// orientation: the classic test for filters and quantisation.

#include <algorithm>

#include "canvas.h"
#include "fixed_cos.h"

namespace testimages::detail {

std::uint32_t zoneplate_level(const Canvas& canvas, int x, int y, int c) {
  // Coordinates doubled so the centre of even-sized images (between two
  // pixels) stays an integer.
  const std::int64_t dx = 2 * std::int64_t(x) - (canvas.width - 1);
  const std::int64_t dy = 2 * std::int64_t(y) - (canvas.height - 1);
  const std::uint64_t r2 = std::uint64_t(dx * dx + dy * dy);  // (2r)^2

  // Phase in turns = r^2 / (4 * rmax) with rmax = max(w, h) / 2, which puts
  // Nyquist at rmax; in doubled coordinates that is r2 / (8 * max(w, h)).
  // Whole turns do not matter, so only the remainder is scaled to 2^32.
  const std::uint64_t period = 8 * std::uint64_t(std::max(canvas.width, canvas.height));
  std::uint32_t phase = std::uint32_t(((r2 % period) << 32) / period);
  // Each channel is shifted by an eighth of a turn.
  phase += std::uint32_t(c) * (std::uint32_t{1} << 29);

  // (1 + cos) / 2 scaled to 0..max_level, rounded.
  const std::int64_t one = std::int64_t{1} << 30;
  const std::uint64_t unit = std::uint64_t(fixed_cos(phase) + one);  // 0..2^31
  return std::uint32_t((unit * canvas.max_level + (std::uint64_t{1} << 30)) >> 31);
}

}  // namespace testimages::detail
