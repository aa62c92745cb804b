// Smooth ramps: the easy case for a wavelet transform, where nearly all
// energy ends up in the low-pass band.

#include "canvas.h"
#include "level_math.h"

namespace testimages::detail {
namespace {

// Ramp from 0 to max_level as pos goes from 0 to span; a zero span (a
// one-pixel-wide axis) has nowhere to ramp and stays at 0.
std::uint32_t ramp(const Canvas& canvas, std::uint64_t pos, std::uint64_t span, int c) {
  const std::uint32_t level = span == 0 ? 0 : lerp_level(0, canvas.max_level, pos, span);
  return channel_variant(level, canvas.max_level, c);
}

}  // namespace

std::uint32_t gradient_h_level(const Canvas& canvas, int x, int, int c) {
  return ramp(canvas, std::uint64_t(x), std::uint64_t(canvas.width - 1), c);
}

std::uint32_t gradient_v_level(const Canvas& canvas, int, int y, int c) {
  return ramp(canvas, std::uint64_t(y), std::uint64_t(canvas.height - 1), c);
}

std::uint32_t gradient_diag_level(const Canvas& canvas, int x, int y, int c) {
  return ramp(canvas, std::uint64_t(x) + std::uint64_t(y),
              std::uint64_t(canvas.width - 1) + std::uint64_t(canvas.height - 1), c);
}

}  // namespace testimages::detail
