#pragma once
#include <cstdint>

namespace codec::t1 {

// Squared-error bookkeeping on the integer coefficient grid for a decoder that places a
// significant coefficient at the middle of its remaining uncertainty interval: with the bit-planes
// down to p known, magnitude m sits in [m_p, m_p + 2^p) where m_p keeps m's bits >= p, and is
// reconstructed as m_p + 2^(p-1); at p = 0 the value is known exactly. 64-bit throughout because
// magnitudes reach 2^31 - 1, whose square needs 62 bits.

inline std::int64_t midpoint_reconstruction(std::uint32_t m, int p) {
  if (p == 0) return m;
  const std::uint64_t known = (static_cast<std::uint64_t>(m) >> p) << p;
  return static_cast<std::int64_t>(known + (std::uint64_t{1} << (p - 1)));
}

inline std::int64_t squared(std::int64_t x) { return x * x; }

// The coefficient becomes significant at plane p: reconstruction 0 -> mid-point.
inline double significance_gain(std::uint32_t m, int p) {
  const std::int64_t before = squared(m);
  const std::int64_t after = squared(static_cast<std::int64_t>(m) - midpoint_reconstruction(m, p));
  return static_cast<double>(before - after);
}

// Plane p's bit of an already significant coefficient: the interval halves.
inline double refinement_gain(std::uint32_t m, int p) {
  const std::int64_t before = squared(static_cast<std::int64_t>(m) - midpoint_reconstruction(m, p + 1));
  const std::int64_t after = squared(static_cast<std::int64_t>(m) - midpoint_reconstruction(m, p));
  return static_cast<double>(before - after);
}

}  // namespace codec::t1
