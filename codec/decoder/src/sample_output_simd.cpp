// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sample_output_simd.cpp"  // found through the src include directory
#include <hwy/foreach_target.h>                      // must precede highway.h
#include <hwy/highway.h>

#include "sample_output.h"

// Bit-exact with the reference rows (sample_output.cpp): the ICT multiplies and adds separately in
// the reference's order, this file is compiled without floating-point contraction (CMakeLists), and
// clamping to the range before rounding to the nearest even integer equals rounding first, since
// the bounds are integers a float holds exactly (the callers below check that). Each row's last
// samples, fewer than a vector, go through the reference row.
HWY_BEFORE_NAMESPACE();
namespace codec::dec {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The clamping bounds before the shift, [lo - shift, hi - shift], and the shift, as lanes.
template <class DI>
struct IntBounds {
  hn::Vec<DI> lo, hi, shift;
  IntBounds(DI di, const SampleRange& r)
      : lo(hn::Set(di, r.lo - r.shift)), hi(hn::Set(di, r.hi - r.shift)), shift(hn::Set(di, r.shift)) {}
  hn::Vec<DI> operator()(hn::Vec<DI> v) const { return hn::Add(hn::Min(hn::Max(v, lo), hi), shift); }
};

template <class DF>
struct FloatBounds {
  hn::Vec<DF> lo, hi;
  hn::Vec<hn::RebindToSigned<DF>> shift;
  FloatBounds(DF df, const SampleRange& r)
      : lo(hn::Set(df, static_cast<float>(r.lo - r.shift))),
        hi(hn::Set(df, static_cast<float>(r.hi - r.shift))),
        shift(hn::Set(hn::RebindToSigned<DF>(), r.shift)) {}
  // Not finite: 0, as the reference.
  hn::Vec<hn::RebindToSigned<DF>> operator()(hn::Vec<DF> f) const {
    f = hn::IfThenElseZero(hn::IsFinite(f), f);
    return hn::Add(hn::NearestInt(hn::Min(hn::Max(f, lo), hi)), shift);
  }
};

void IntsToSamples(const std::int32_t* HWY_RESTRICT in, const SampleRange& range, std::int32_t* HWY_RESTRICT out,
                   std::size_t n) {
  const hn::ScalableTag<std::int32_t> di;
  const std::size_t N = hn::Lanes(di);
  const IntBounds<decltype(di)> bounds(di, range);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(bounds(hn::LoadU(di, in + i)), di, out + i);
  reference::ints_to_samples(in + i, range, out + i, n - i);
}

void FloatsToSamples(const float* HWY_RESTRICT in, const SampleRange& range, std::int32_t* HWY_RESTRICT out,
                     std::size_t n) {
#if HWY_TARGET == HWY_SCALAR
  return reference::floats_to_samples(in, range, out, n);  // its NearestInt may round 0.5 - ulp up
#endif
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const std::size_t N = hn::Lanes(df);
  const FloatBounds<decltype(df)> bounds(df, range);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(bounds(hn::LoadU(df, in + i)), di, out + i);
  reference::floats_to_samples(in + i, range, out + i, n - i);
}

void RctToSamples(const std::int32_t* HWY_RESTRICT y, const std::int32_t* HWY_RESTRICT cb,
                  const std::int32_t* HWY_RESTRICT cr, const OutputRanges& ranges, const OutputRows& out,
                  std::size_t n) {
  const hn::ScalableTag<std::int32_t> di;
  const std::size_t N = hn::Lanes(di);
  const IntBounds<decltype(di)> r_bounds(di, ranges[0]), g_bounds(di, ranges[1]), b_bounds(di, ranges[2]);
  const auto three = hn::Set(di, 3);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto vy = hn::LoadU(di, y + i), vcb = hn::LoadU(di, cb + i), vcr = hn::LoadU(di, cr + i);
    // floor((Cb + Cr) / 4) without the sum, which may overflow 32 bits: the quarters' sum plus
    // the quarter of the remainders' sum.
    const auto quarter = hn::Add(hn::Add(hn::ShiftRight<2>(vcb), hn::ShiftRight<2>(vcr)),
                                 hn::ShiftRight<2>(hn::Add(hn::And(vcb, three), hn::And(vcr, three))));
    const auto g = hn::Sub(vy, quarter);
    if (out[0]) hn::StoreU(r_bounds(hn::Add(vcr, g)), di, out[0] + i);
    if (out[1]) hn::StoreU(g_bounds(g), di, out[1] + i);
    if (out[2]) hn::StoreU(b_bounds(hn::Add(vcb, g)), di, out[2] + i);
  }
  const OutputRows rest = {out[0] ? out[0] + i : nullptr, out[1] ? out[1] + i : nullptr, out[2] ? out[2] + i : nullptr};
  reference::rct_to_samples(y + i, cb + i, cr + i, ranges, rest, n - i);
}

void IctToSamples(const float* HWY_RESTRICT y, const float* HWY_RESTRICT cb, const float* HWY_RESTRICT cr,
                  const OutputRanges& ranges, const OutputRows& out, std::size_t n) {
#if HWY_TARGET == HWY_SCALAR
  return reference::ict_to_samples(y, cb, cr, ranges, out, n);  // as FloatsToSamples
#endif
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const std::size_t N = hn::Lanes(df);
  const FloatBounds<decltype(df)> r_bounds(df, ranges[0]), g_bounds(df, ranges[1]), b_bounds(df, ranges[2]);
  const auto r_cr = hn::Set(df, 1.402f), g_cb = hn::Set(df, 0.34413f), g_cr = hn::Set(df, 0.71414f),
             b_cb = hn::Set(df, 1.772f);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto vy = hn::LoadU(df, y + i), vcb = hn::LoadU(df, cb + i), vcr = hn::LoadU(df, cr + i);
    if (out[0]) hn::StoreU(r_bounds(hn::Add(vy, hn::Mul(r_cr, vcr))), di, out[0] + i);
    if (out[1]) hn::StoreU(g_bounds(hn::Sub(hn::Sub(vy, hn::Mul(g_cb, vcb)), hn::Mul(g_cr, vcr))), di, out[1] + i);
    if (out[2]) hn::StoreU(b_bounds(hn::Add(vy, hn::Mul(b_cb, vcb))), di, out[2] + i);
  }
  const OutputRows rest = {out[0] ? out[0] + i : nullptr, out[1] ? out[1] + i : nullptr, out[2] ? out[2] + i : nullptr};
  reference::ict_to_samples(y + i, cb + i, cr + i, ranges, rest, n - i);
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::dec
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::dec {
HWY_EXPORT(IntsToSamples);
HWY_EXPORT(FloatsToSamples);
HWY_EXPORT(RctToSamples);
HWY_EXPORT(IctToSamples);

namespace {
// Whether the float lanes clamp to the range exactly: its bounds before the shift are integers of
// at most 24 bits (components of up to 25 bits).
bool floats_hold(const SampleRange& r) {
  constexpr std::int64_t kExact = std::int64_t{1} << 24;
  return std::int64_t{r.lo} - r.shift >= -kExact && std::int64_t{r.hi} - r.shift <= kExact;
}
}  // namespace

void ints_to_samples(const std::int32_t* in, const SampleRange& range, std::int32_t* out, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(IntsToSamples)(in, range, out, n);
}

void floats_to_samples(const float* in, const SampleRange& range, std::int32_t* out, std::size_t n) {
  if (!floats_hold(range)) return reference::floats_to_samples(in, range, out, n);
  HWY_DYNAMIC_DISPATCH(FloatsToSamples)(in, range, out, n);
}

void rct_to_samples(const std::int32_t* y, const std::int32_t* cb, const std::int32_t* cr, const OutputRanges& ranges,
                    const OutputRows& out, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(RctToSamples)(y, cb, cr, ranges, out, n);
}

void ict_to_samples(const float* y, const float* cb, const float* cr, const OutputRanges& ranges, const OutputRows& out,
                    std::size_t n) {
  if (!floats_hold(ranges[0]) || !floats_hold(ranges[1]) || !floats_hold(ranges[2]))
    return reference::ict_to_samples(y, cb, cr, ranges, out, n);
  HWY_DYNAMIC_DISPATCH(IctToSamples)(y, cb, cr, ranges, out, n);
}

}  // namespace codec::dec
#endif
