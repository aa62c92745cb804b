// Uniform white noise: incompressible, so it exercises the entropy coder's
// worst case and every bit plane.

#include "canvas.h"
#include "testimages/prng.h"

namespace testimages::detail {

std::uint32_t noise_level(const Canvas& canvas, int x, int y, int c) {
  // One PRNG output per sample, indexed by the sample's position, so the
  // value does not depend on the order in which samples are generated.
  const std::uint64_t index =
      (std::uint64_t(y) * std::uint64_t(canvas.width) + std::uint64_t(x)) * std::uint64_t(canvas.channels) +
      std::uint64_t(c);
  // The top bits of SplitMix64 are uniformly distributed; taking them is
  // exact, unlike a modulo or a <random> distribution.
  return std::uint32_t(splitmix64_at(canvas.seed, index) >> (64 - canvas.bits));
}

}  // namespace testimages::detail
