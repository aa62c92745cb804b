#include "sample_output.h"

#include <algorithm>
#include <cmath>

namespace codec::dec {

SampleRange sample_range(int precision, bool is_signed) {
  const std::int64_t half = std::int64_t{1} << (precision - 1);
  SampleRange r;
  r.shift = is_signed ? 0 : static_cast<std::int32_t>(half);
  r.lo = is_signed ? static_cast<std::int32_t>(-half) : 0;
  r.hi = static_cast<std::int32_t>(is_signed ? half - 1 : 2 * half - 1);
  return r;
}

WideSampleRange wide_sample_range(int precision, bool is_signed) {
  const std::int64_t half = std::int64_t{1} << (precision - 1);
  return is_signed ? WideSampleRange{0, -half, half - 1} : WideSampleRange{half, 0, 2 * half - 1};
}

std::int64_t wide_sample(std::int64_t v, const WideSampleRange& range) {
  // Saturating first: a hostile stream's coefficients may be anywhere in int64.
  constexpr std::int64_t kReach = std::int64_t{1} << 62;
  return std::clamp(std::clamp(v, -kReach, kReach) + range.shift, range.lo, range.hi);
}

std::int64_t wide_sample(double v, const WideSampleRange& range) {
  constexpr double kReach = 0x1p62;
  if (!std::isfinite(v)) return wide_sample(std::int64_t{0}, range);
  return wide_sample(static_cast<std::int64_t>(std::nearbyint(std::clamp(v, -kReach, kReach))), range);
}

std::int64_t inverse_rct(std::int64_t y, std::int64_t cb, std::int64_t cr, std::size_t c) {
  // G-7 in wrapping arithmetic (hostile values may overflow; wide_sample then clamps them).
  auto add = [](std::int64_t a, std::int64_t b) {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
  };
  const std::int64_t g =
      static_cast<std::int64_t>(static_cast<std::uint64_t>(y) - static_cast<std::uint64_t>(add(cb, cr) >> 2));
  return c == 0 ? add(cr, g) : c == 1 ? g : add(cb, g);
}

double inverse_ict(double y, double cb, double cr, std::size_t c) {
  // G-9, with T.800's coefficients, as ict_to_samples.
  return c == 0 ? y + 1.402 * cr : c == 1 ? y - 0.34413 * cb - 0.71414 * cr : y + 1.772 * cb;
}

namespace reference {
namespace {

// G.1.2: the level shift, then the component's range.
std::int32_t shifted_and_clamped(std::int64_t v, const SampleRange& r) {
  return static_cast<std::int32_t>(std::clamp(v + r.shift, std::int64_t{r.lo}, std::int64_t{r.hi}));
}

// A 9/7 sample to the nearest integer (ties to even, as lrint in the default rounding mode); what
// is not a finite number becomes 0.
std::int64_t rounded(float f) {
  return std::isfinite(f) ? static_cast<std::int64_t>(std::lrint(std::clamp(f, -1e12f, 1e12f))) : 0;
}

// Two's complement sums: a hostile stream's coefficients may overflow, and wrap like the vector lanes.
std::int32_t wrapping_add(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) + static_cast<std::uint32_t>(b));
}
std::int32_t wrapping_sub(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) - static_cast<std::uint32_t>(b));
}

}  // namespace

void ints_to_samples(const std::int32_t* in, const SampleRange& range, std::int32_t* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = shifted_and_clamped(in[i], range);
}

void floats_to_samples(const float* in, const SampleRange& range, std::int32_t* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = shifted_and_clamped(rounded(in[i]), range);
}

void rct_to_samples(const std::int32_t* y, const std::int32_t* cb, const std::int32_t* cr, const OutputRanges& ranges,
                    const OutputRows& out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    // G-7: G = Y - floor((Cb + Cr) / 4); R = Cr + G; B = Cb + G (arithmetic shift is floor).
    const std::int32_t g = wrapping_sub(y[i], static_cast<std::int32_t>((std::int64_t{cb[i]} + cr[i]) >> 2));
    const std::int32_t rgb[3] = {wrapping_add(cr[i], g), g, wrapping_add(cb[i], g)};
    for (std::size_t c = 0; c < 3; ++c)
      if (out[c]) out[c][i] = shifted_and_clamped(rgb[c], ranges[c]);
  }
}

void ict_to_samples(const float* y, const float* cb, const float* cr, const OutputRanges& ranges, const OutputRows& out,
                    std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    // G-9, with T.800's coefficients; multiplied and added in this order, without contraction
    // (CMakeLists), as the vector rows do.
    const float rgb[3] = {y[i] + 1.402f * cr[i], y[i] - 0.34413f * cb[i] - 0.71414f * cr[i], y[i] + 1.772f * cb[i]};
    for (std::size_t c = 0; c < 3; ++c)
      if (out[c]) out[c][i] = shifted_and_clamped(rounded(rgb[c]), ranges[c]);
  }
}

}  // namespace reference
}  // namespace codec::dec
