#include "coefficient_state.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "block_loading_simd.h"
#include "codec/t1/dead_zone.h"
#include "codec/t1/stripe_columns.h"

namespace codec::t1 {

namespace {
constexpr int kFractionBits = 8;  // as given: 1/256ths

// The calling thread's arrays behind its CoefficientState.
struct Workspace {
  std::vector<std::uint32_t> columns, magnitude, fine, column_magnitudes;
  std::vector<std::uint16_t> signs;
};

Workspace& workspace() {
  thread_local Workspace w;
  return w;
}

// `v` sized to n elements (capacity kept from earlier blocks), contents left as they are.
template <class T>
std::span<T> sized(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
  return {v.data(), n};
}
}  // namespace

CoefficientState::CoefficientState(int width, int height) : width_(width), height_(height), stride_(width + 2) {
  Workspace& w = workspace();
  const auto coefficients = static_cast<std::size_t>(stride_ * (height + 2));
  columns_ = sized(w.columns, static_cast<std::size_t>(stride_ * ((height + 3) / 4 + 2)));
  std::fill(columns_.begin(), columns_.end(), 0u);
  signs_ = sized(w.signs, coefficients);
  magnitude_ = sized(w.magnitude, coefficients);
}

template <class F>
void CoefficientState::for_each_coefficient(F&& f) const {
  for (int y = 0; y < height_; ++y) {
    const auto row = static_cast<std::size_t>((y + 1) * stride_ + 1);
    for (int x = 0; x < width_; ++x) f(row + static_cast<std::size_t>(x));
  }
}

template <class Sample>
void CoefficientState::load(Sample&& sample, bool with_fractions) {
  // The fractions wait in fine_ until the bit-planes, and so the fixed point, are known.
  if (with_fractions) fine_ = sized(workspace().fine, magnitude_.size());
  std::uint32_t any_bits = 0;
  for (int y = 0; y < height_; ++y) {
    const auto row = static_cast<std::size_t>((y + 1) * stride_ + 1);
    for (int x = 0; x < width_; ++x) {
      std::uint8_t fraction = 0;
      const std::int32_t c = sample(x, y, fraction);
      // Negate in unsigned arithmetic: -INT32_MIN would overflow (the caller's Mb check rejects it).
      const std::uint32_t m = c < 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
      const std::size_t i = row + static_cast<std::size_t>(x);
      magnitude_[i] = m;
      signs_[i] = c < 0 ? std::uint16_t{kNeg} : std::uint16_t{0};
      if (with_fractions) fine_[i] = fraction;
      any_bits |= m;
    }
  }
  // The OR of all magnitudes has the same highest set bit as their maximum, and is cheaper.
  bit_planes_ = static_cast<int>(std::bit_width(any_bits));

  if (!with_fractions) {
    for_each_coefficient([&](std::size_t i) {
      const auto m = static_cast<double>(magnitude_[i]);
      energy_ += m * m;
    });
    return;
  }
  // As many fraction bits as keep the fixed-point magnitude below 2^31, the range the distortion
  // arithmetic is proven for (distortion.h); all 8 unless the block uses more than 23 planes.
  fine_bits_ = std::clamp(31 - bit_planes_, 0, kFractionBits);
  const double unit = std::ldexp(1.0, -fine_bits_);
  for_each_coefficient([&](std::size_t i) {
    fine_[i] = magnitude_[i] << fine_bits_ | fine_[i] >> (kFractionBits - fine_bits_);
    const double u = static_cast<double>(fine_[i]) * unit;
    energy_ += u * u;
  });
}

CoefficientState::CoefficientState(std::span<const std::int32_t> coefficients, int width, int height,
                                   std::span<const std::uint8_t> fractions)
    : CoefficientState(width, height) {
  const auto w = static_cast<std::size_t>(width);
  load(
      [&](int x, int y, std::uint8_t& fraction) {
        const std::size_t i = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
        if (!fractions.empty()) fraction = fractions[i];
        return coefficients[i];
      },
      !fractions.empty());
}

CoefficientState::CoefficientState(const IntegerBlock& block) : CoefficientState(block.width, block.height) {
  std::uint32_t any_bits = 0;
  for (int y = 0; y < height_; ++y) {
    const auto i = static_cast<std::size_t>((y + 1) * stride_ + 1);
    any_bits |= simd::load_index_row(block.origin + y * block.stride, static_cast<std::size_t>(width_),
                                     magnitude_.data() + i, signs_.data() + i, energy_);
  }
  bit_planes_ = static_cast<int>(std::bit_width(any_bits));
}

namespace {
FloatBlockPlanes planes_of_peak(float peak) {
  FloatBlockPlanes planes;
  planes.bit_planes = static_cast<int>(std::bit_width(static_cast<std::uint32_t>(static_cast<std::int32_t>(peak))));
  planes.fine_bits = std::clamp(31 - planes.bit_planes, 0, kFractionBits);
  return planes;
}
}  // namespace

FloatBlockPlanes float_block_planes(const FloatBlock& block) {
  const auto w = static_cast<std::size_t>(block.width);
  float peak = 0;
  for (int y = 0; y < block.height; ++y)
    peak = std::max(peak, simd::peak_scaled_magnitude(block.origin + y * block.stride, w, block.inverse_step));
  return planes_of_peak(peak);
}

FloatBlockSurvey survey_float_block(const FloatBlock& block) {
  const auto w = static_cast<std::size_t>(block.width);
  float peak = 0;
  double sum = 0;  // in 1/256ths squared
  // The block is usually cold (the DWT wrote it long ago) and its rows lie a plane's width apart,
  // which the hardware prefetcher does not follow: ask for every line up front, so that the misses
  // overlap instead of coming one row at a time.
  constexpr std::size_t kLine = 64 / sizeof(float);
  for (int y = 0; y < block.height; ++y)
    for (std::size_t x = 0; x < w; x += kLine) __builtin_prefetch(block.origin + y * block.stride + x);
  for (int y = 0; y < block.height; ++y)
    sum += simd::peak_and_energy_row(block.origin + y * block.stride, w, block.inverse_step, peak);
  FloatBlockSurvey survey;
  survey.planes = planes_of_peak(peak);
  survey.energy = survey.planes.fine_bits == kFractionBits ? std::ldexp(sum, -2 * kFractionBits)
                                                           : float_block_energy(block, survey.planes);
  return survey;
}

double float_block_energy(const FloatBlock& block, const FloatBlockPlanes& planes) {
  const auto w = static_cast<std::size_t>(block.width);
  double sum = 0;
  for (int y = 0; y < block.height; ++y)
    sum += simd::fixed_point_energy_row(block.origin + y * block.stride, w, block.inverse_step, planes.fine_bits);
  return std::ldexp(sum, -2 * planes.fine_bits);
}

CoefficientState::CoefficientState(const FloatBlock& block) : CoefficientState(block, float_block_planes(block)) {}

// The same as load() with the fractions of quantize() (dead_zone.h), in two vectorised sweeps:
// quantisation is monotonic in |c|, so the largest magnitude gives the bit-planes and with them the
// fixed point (float_block_planes), and then fine = floor(|c| / step * 2^F) is the index with the F
// leading bits of its fraction appended, exactly as load() assembles it.
CoefficientState::CoefficientState(const FloatBlock& block, const FloatBlockPlanes& planes)
    : CoefficientState(block.width, block.height) {
  const auto w = static_cast<std::size_t>(width_);
  bit_planes_ = planes.bit_planes;
  fine_bits_ = planes.fine_bits;
  fine_ = sized(workspace().fine, magnitude_.size());
  double sum = 0;
  for (int y = 0; y < height_; ++y) {
    const auto i = static_cast<std::size_t>((y + 1) * stride_ + 1);
    sum += simd::quantize_row(block.origin + y * block.stride, w, block.inverse_step, fine_bits_, fine_.data() + i,
                              magnitude_.data() + i, signs_.data() + i);
  }
  energy_ = std::ldexp(sum, -2 * fine_bits_);
}

BlockView CoefficientState::view(bool causal) {
  const std::ptrdiff_t origin = stride_ + 1;
  column_magnitudes_ = sized(workspace().column_magnitudes, columns_.size());
  for (int y0 = 0; y0 < height_; y0 += 4)
    simd::or_stripe_rows(magnitude_.data() + origin + y0 * stride_, stride_, std::min(4, height_ - y0),
                         static_cast<std::size_t>(width_), column_magnitudes_.data() + origin + (y0 / 4) * stride_);
  const std::uint32_t* fine = fine_.empty() ? magnitude_.data() : fine_.data();
  return BlockView{columns_.data() + origin,
                   stride_,
                   magnitude_.data() + origin,
                   signs_.data() + origin,
                   width_,
                   height_,
                   stride_,
                   causal,
                   fine + origin,
                   fine_bits_,
                   column_magnitudes_.data() + origin};
}

}  // namespace codec::t1
