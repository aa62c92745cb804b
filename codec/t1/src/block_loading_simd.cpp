// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/block_loading_simd.cpp"
#include <hwy/foreach_target.h>  // must precede highway.h
#include <hwy/highway.h>

#include "block_loading_simd.h"
#include "codec/t1/dead_zone.h"
#include "codec/t1/stripe_columns.h"

// The scalar tails repeat the vector arithmetic operation for operation (IEEE single precision,
// truncating conversions), so a coefficient gets the same bits whichever lane or tail codes it.
HWY_BEFORE_NAMESPACE();
namespace codec::t1::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Adds the squares of the lanes of `v` (non-negative int32) to `sum`, in double precision: a
// double vector holds half as many lanes, except on the one-lane scalar target.
#if HWY_TARGET == HWY_SCALAR
template <class DI>
using DoubleTag = hn::Rebind<double, DI>;
template <class DI, class VI, class VD>
HWY_INLINE VD AddSquares(DI, VI v, VD sum) {
  const auto x = hn::PromoteTo(DoubleTag<DI>(), v);
  return hn::MulAdd(x, x, sum);
}
#else
template <class DI>
using DoubleTag = hn::Rebind<double, hn::Half<DI> >;
template <class DI, class VI, class VD>
HWY_INLINE VD AddSquares(DI, VI v, VD sum) {
  const hn::Half<DI> dh;
  const DoubleTag<DI> dd;
  const auto lo = hn::PromoteTo(dd, hn::LowerHalf(dh, v));
  const auto hi = hn::PromoteTo(dd, hn::UpperHalf(dh, v));
  return hn::MulAdd(hi, hi, hn::MulAdd(lo, lo, sum));
}
#endif

float PeakScaledMagnitude(const float* HWY_RESTRICT row, std::size_t n, float inverse_step) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  const auto inverse = hn::Set(d, inverse_step);
  const auto largest = hn::Set(d, kLargestMagnitude);
  auto peak = hn::Zero(d);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto m = hn::Mul(hn::Abs(hn::LoadU(d, row + i)), inverse);
    peak = hn::Max(peak, hn::IfThenElse(hn::Lt(m, largest), m, largest));  // NaN: the clamp, as scaled_magnitude
  }
  float result = hn::GetLane(hn::MaxOfLanes(d, peak));
  for (; i < n; ++i) {
    const float m = scaled_magnitude(row[i], inverse_step);
    result = m > result ? m : result;
  }
  return result;
}

double QuantizeRow(const float* HWY_RESTRICT row, std::size_t n, float inverse_step, int fine_bits,
                   std::uint32_t* HWY_RESTRICT fine, std::uint32_t* HWY_RESTRICT magnitude,
                   std::uint16_t* HWY_RESTRICT flags) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::Rebind<std::uint16_t, decltype(di)> d16;
  const DoubleTag<decltype(di)> dd;
  const std::size_t N = hn::Lanes(df);
  const float scale = static_cast<float>(1u << fine_bits);
  const auto inverse = hn::Set(df, inverse_step);
  const auto largest = hn::Set(df, kLargestMagnitude);
  const auto to_fixed = hn::Set(df, scale);
  const auto negative_flag = hn::Set(di, kNeg);
  auto energy = hn::Zero(dd);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto c = hn::LoadU(df, row + i);
    auto m = hn::Mul(hn::Abs(c), inverse);
    m = hn::IfThenElse(hn::Lt(m, largest), m, largest);
    // Exact: a power-of-two scale, and the product stays below 2^31 (the caller's fine_bits).
    const auto f = hn::ConvertTo(di, hn::Mul(m, to_fixed));
    const auto q = hn::ShiftRightSame(f, fine_bits);
    hn::StoreU(hn::BitCast(du, f), du, fine + i);
    hn::StoreU(hn::BitCast(du, q), du, magnitude + i);
    const auto negative = hn::And(hn::RebindMask(di, hn::Lt(c, hn::Zero(df))), hn::Ne(q, hn::Zero(di)));
    hn::StoreU(hn::DemoteTo(d16, hn::IfThenElseZero(negative, negative_flag)), d16, flags + i);
    energy = AddSquares(di, f, energy);
  }
  double result = hn::GetLane(hn::SumOfLanes(dd, energy));
  for (; i < n; ++i) {
    const float c = row[i];
    const auto f = static_cast<std::uint32_t>(static_cast<std::int32_t>(scaled_magnitude(c, inverse_step) * scale));
    const std::uint32_t q = f >> fine_bits;
    fine[i] = f;
    magnitude[i] = q;
    flags[i] = c < 0 && q != 0 ? std::uint16_t{kNeg} : std::uint16_t{0};
    result += static_cast<double>(f) * static_cast<double>(f);
  }
  return result;
}

double FixedPointEnergyRow(const float* HWY_RESTRICT row, std::size_t n, float inverse_step, int fine_bits) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const DoubleTag<decltype(di)> dd;
  const std::size_t N = hn::Lanes(df);
  const float scale = static_cast<float>(1u << fine_bits);
  const auto inverse = hn::Set(df, inverse_step);
  const auto largest = hn::Set(df, kLargestMagnitude);
  const auto to_fixed = hn::Set(df, scale);
  auto energy = hn::Zero(dd);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {  // QuantizeRow's arithmetic, without the stores
    auto m = hn::Mul(hn::Abs(hn::LoadU(df, row + i)), inverse);
    m = hn::IfThenElse(hn::Lt(m, largest), m, largest);
    energy = AddSquares(di, hn::ConvertTo(di, hn::Mul(m, to_fixed)), energy);
  }
  double result = hn::GetLane(hn::SumOfLanes(dd, energy));
  for (; i < n; ++i) {
    const auto f =
        static_cast<std::uint32_t>(static_cast<std::int32_t>(scaled_magnitude(row[i], inverse_step) * scale));
    result += static_cast<double>(f) * static_cast<double>(f);
  }
  return result;
}

double PeakAndEnergyRow(const float* HWY_RESTRICT row, std::size_t n, float inverse_step, float& peak_out) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const DoubleTag<decltype(di)> dd;
  const std::size_t N = hn::Lanes(df);
  constexpr float kScale = 256.0f;  // 8 fraction bits
  const auto inverse = hn::Set(df, inverse_step);
  const auto largest = hn::Set(df, kLargestMagnitude);
  const auto to_fixed = hn::Set(df, kScale);
  auto energy = hn::Zero(dd);
  auto peak = hn::Zero(df);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {  // FixedPointEnergyRow's arithmetic, and the peak
    auto m = hn::Mul(hn::Abs(hn::LoadU(df, row + i)), inverse);
    m = hn::IfThenElse(hn::Lt(m, largest), m, largest);
    peak = hn::Max(peak, m);
    energy = AddSquares(di, hn::ConvertTo(di, hn::Mul(m, to_fixed)), energy);
  }
  double result = hn::GetLane(hn::SumOfLanes(dd, energy));
  float highest = hn::GetLane(hn::MaxOfLanes(df, peak));
  for (; i < n; ++i) {
    const float m = scaled_magnitude(row[i], inverse_step);
    highest = m > highest ? m : highest;
    if (m * kScale >= 2147483648.0f) continue;  // the sum is void then (see the header); no overflowing cast
    const auto f = static_cast<std::uint32_t>(static_cast<std::int32_t>(m * kScale));
    result += static_cast<double>(f) * static_cast<double>(f);
  }
  peak_out = highest > peak_out ? highest : peak_out;
  return result;
}

std::uint32_t LoadIndexRow(const std::int32_t* HWY_RESTRICT row, std::size_t n, std::uint32_t* HWY_RESTRICT magnitude,
                           std::uint16_t* HWY_RESTRICT flags, double& energy_sum) {
  const hn::ScalableTag<std::int32_t> di;
  const hn::RebindToUnsigned<decltype(di)> du;
  const hn::Rebind<std::uint16_t, decltype(di)> d16;
  const DoubleTag<decltype(di)> dd;
  const std::size_t N = hn::Lanes(di);
  const auto negative_flag = hn::Set(di, kNeg);
  auto any = hn::Zero(du);
  auto energy = hn::Zero(dd);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto c = hn::LoadU(di, row + i);
    // |c| wraps INT32_MIN to itself, which read unsigned is 2^31: the unsigned negation.
    const auto a = hn::Abs(c);
    const auto m = hn::BitCast(du, a);
    hn::StoreU(m, du, magnitude + i);
    hn::StoreU(hn::DemoteTo(d16, hn::IfThenElseZero(hn::Lt(c, hn::Zero(di)), negative_flag)), d16, flags + i);
    any = hn::Or(any, m);
    energy = AddSquares(di, a, energy);  // INT32_MIN's comes out wrong, but needs 32 planes: refused
  }
  double energy_tail = hn::GetLane(hn::SumOfLanes(dd, energy));
  // OR across lanes: no OrOfLanes in this Highway, so through memory.
  HWY_ALIGN std::uint32_t lanes[hn::MaxLanes(du)];
  hn::Store(any, du, lanes);
  std::uint32_t result = 0;
  for (std::size_t k = 0; k < N; ++k) result |= lanes[k];
  for (; i < n; ++i) {
    const std::int32_t c = row[i];
    const std::uint32_t m = c < 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
    magnitude[i] = m;
    flags[i] = c < 0 ? std::uint16_t{kNeg} : std::uint16_t{0};
    result |= m;
    energy_tail += static_cast<double>(m) * static_cast<double>(m);
  }
  energy_sum += energy_tail;
  return result;
}

void OrStripeRows(const std::uint32_t* HWY_RESTRICT rows, std::ptrdiff_t stride, int rows_in_stripe, std::size_t n,
                  std::uint32_t* HWY_RESTRICT out) {
  const hn::ScalableTag<std::uint32_t> du;
  const std::size_t N = hn::Lanes(du);
  std::size_t x = 0;
  for (; x + N <= n; x += N) {
    auto v = hn::LoadU(du, rows + x);
    for (int r = 1; r < rows_in_stripe; ++r) v = hn::Or(v, hn::LoadU(du, rows + r * stride + x));
    hn::StoreU(v, du, out + x);
  }
  for (; x < n; ++x) {
    std::uint32_t v = rows[x];
    for (int r = 1; r < rows_in_stripe; ++r) v |= rows[r * stride + x];
    out[x] = v;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::t1::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::t1::simd {
HWY_EXPORT(PeakScaledMagnitude);
HWY_EXPORT(QuantizeRow);
HWY_EXPORT(LoadIndexRow);
HWY_EXPORT(FixedPointEnergyRow);
HWY_EXPORT(OrStripeRows);
HWY_EXPORT(PeakAndEnergyRow);

float peak_scaled_magnitude(const float* row, std::size_t n, float inverse_step) {
  return HWY_DYNAMIC_DISPATCH(PeakScaledMagnitude)(row, n, inverse_step);
}

double quantize_row(const float* row, std::size_t n, float inverse_step, int fine_bits, std::uint32_t* fine,
                    std::uint32_t* magnitude, std::uint16_t* flags) {
  return HWY_DYNAMIC_DISPATCH(QuantizeRow)(row, n, inverse_step, fine_bits, fine, magnitude, flags);
}

double fixed_point_energy_row(const float* row, std::size_t n, float inverse_step, int fine_bits) {
  return HWY_DYNAMIC_DISPATCH(FixedPointEnergyRow)(row, n, inverse_step, fine_bits);
}

std::uint32_t load_index_row(const std::int32_t* row, std::size_t n, std::uint32_t* magnitude, std::uint16_t* flags,
                             double& energy) {
  return HWY_DYNAMIC_DISPATCH(LoadIndexRow)(row, n, magnitude, flags, energy);
}

double peak_and_energy_row(const float* row, std::size_t n, float inverse_step, float& peak) {
  return HWY_DYNAMIC_DISPATCH(PeakAndEnergyRow)(row, n, inverse_step, peak);
}

void or_stripe_rows(const std::uint32_t* rows, std::ptrdiff_t stride, int rows_in_stripe, std::size_t n,
                    std::uint32_t* out) {
  HWY_DYNAMIC_DISPATCH(OrStripeRows)(rows, stride, rows_in_stripe, n, out);
}

}  // namespace codec::t1::simd
#endif
