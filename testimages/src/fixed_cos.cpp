#include "fixed_cos.h"

namespace testimages::detail {
namespace {

constexpr int kFracBits = 30;
constexpr std::int64_t kOne = std::int64_t{1} << kFracBits;
// round(pi/2 * 2^30)
constexpr std::int64_t kHalfPi = 1686629713;

constexpr std::int64_t mul(std::int64_t a, std::int64_t b) { return (a * b) >> kFracBits; }

// Taylor series in Horner form for 0 <= x <= pi/2 (Q30). Terms up to x^15
// and x^14 keep the truncation error below 1e-9 over that interval; every
// intermediate stays below 2^62.
std::int64_t sin_q(std::int64_t x) {
  const std::int64_t x2 = mul(x, x);
  std::int64_t t = kOne;
  for (int n = 14; n >= 2; n -= 2) t = kOne - mul(x2, t) / (n * (n + 1));
  return mul(x, t);
}

std::int64_t cos_q(std::int64_t x) {
  const std::int64_t x2 = mul(x, x);
  std::int64_t t = kOne;
  for (int n = 13; n >= 1; n -= 2) t = kOne - mul(x2, t) / (n * (n + 1));
  return t;
}

}  // namespace

std::int64_t fixed_cos(std::uint32_t phase) {
  const std::uint32_t quadrant = phase >> 30;
  const std::int64_t within = phase & ((std::uint32_t{1} << 30) - 1);
  const std::int64_t x = (within * kHalfPi) >> 30;  // angle within the quadrant
  std::int64_t value = 0;
  switch (quadrant) {
    case 0:
      value = cos_q(x);
      break;
    case 1:
      value = -sin_q(x);
      break;
    case 2:
      value = -cos_q(x);
      break;
    default:
      value = sin_q(x);
      break;
  }
  // Rounding can overshoot +-1 by an ulp; keep callers' ranges exact.
  if (value > kOne) return kOne;
  if (value < -kOne) return -kOne;
  return value;
}

}  // namespace testimages::detail
