// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "component_transform_simd.cpp"  // found through the src include directory
#include <hwy/foreach_target.h>                            // must precede highway.h
#include <hwy/highway.h>

#include "component_transform_simd.h"

// Bit-exact with the scalar rows: the ICT multiplies and adds separately, in the scalar order
// ((a r + b g) + c b), and this file is compiled without floating-point contraction (CMakeLists),
// so no multiply-add fuses on the targets that have one.
HWY_BEFORE_NAMESPACE();
namespace codec::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The row's samples as int32 lanes, shifted: r - shift_r and so on, for pixels i .. i + lanes - 1.
template <class DI>
HWY_INLINE void LoadShiftedRgb(DI di, const std::uint8_t* HWY_RESTRICT rgb, std::size_t i, hn::Vec<DI> shift_r,
                               hn::Vec<DI> shift_g, hn::Vec<DI> shift_b, hn::Vec<DI>& r, hn::Vec<DI>& g,
                               hn::Vec<DI>& b) {
  const hn::Rebind<std::uint8_t, DI> d8;
  hn::Vec<decltype(d8)> r8, g8, b8;
  hn::LoadInterleaved3(d8, rgb + 3 * i, r8, g8, b8);
  r = hn::Sub(hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<DI>(), r8)), shift_r);
  g = hn::Sub(hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<DI>(), g8)), shift_g);
  b = hn::Sub(hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<DI>(), b8)), shift_b);
}

void RctForwardRgb8(const std::uint8_t* HWY_RESTRICT rgb, std::int32_t shift_r, std::int32_t shift_g,
                    std::int32_t shift_b, std::int32_t* HWY_RESTRICT y, std::int32_t* HWY_RESTRICT cb,
                    std::int32_t* HWY_RESTRICT cr, std::size_t n) {
  const hn::ScalableTag<std::int32_t> di;
  const std::size_t N = hn::Lanes(di);
  const auto sr = hn::Set(di, shift_r), sg = hn::Set(di, shift_g), sb = hn::Set(di, shift_b);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    hn::Vec<decltype(di)> r, g, b;
    LoadShiftedRgb(di, rgb, i, sr, sg, sb, r, g, b);
    // T.800 G-5: an arithmetic shift is the floor the standard asks for, negative sums included.
    hn::StoreU(hn::ShiftRight<2>(hn::Add(hn::Add(r, hn::Add(g, g)), b)), di, y + i);
    hn::StoreU(hn::Sub(b, g), di, cb + i);
    hn::StoreU(hn::Sub(r, g), di, cr + i);
  }
  for (; i < n; ++i) {
    const std::int32_t r = rgb[3 * i] - shift_r, g = rgb[3 * i + 1] - shift_g, b = rgb[3 * i + 2] - shift_b;
    y[i] = (r + 2 * g + b) >> 2;
    cb[i] = b - g;
    cr[i] = r - g;
  }
}

void IctForwardRgb8(const std::uint8_t* HWY_RESTRICT rgb, std::int32_t shift_r, std::int32_t shift_g,
                    std::int32_t shift_b, float* HWY_RESTRICT y, float* HWY_RESTRICT cb, float* HWY_RESTRICT cr,
                    std::size_t n) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const std::size_t N = hn::Lanes(df);
  const auto sr = hn::Set(di, shift_r), sg = hn::Set(di, shift_g), sb = hn::Set(di, shift_b);
  // T.800 G-9's coefficients, as component_transform.cpp writes them.
  const auto yr = hn::Set(df, 0.299f), yg = hn::Set(df, 0.587f), yb = hn::Set(df, 0.114f);
  const auto br = hn::Set(df, -0.16875f), bg = hn::Set(df, -0.33126f), bb = hn::Set(df, 0.5f);
  const auto rr = hn::Set(df, 0.5f), rg = hn::Set(df, -0.41869f), rb = hn::Set(df, -0.08131f);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    hn::Vec<decltype(di)> ri, gi, bi;
    LoadShiftedRgb(di, rgb, i, sr, sg, sb, ri, gi, bi);
    const auto r = hn::ConvertTo(df, ri), g = hn::ConvertTo(df, gi), b = hn::ConvertTo(df, bi);
    hn::StoreU(hn::Add(hn::Add(hn::Mul(yr, r), hn::Mul(yg, g)), hn::Mul(yb, b)), df, y + i);
    hn::StoreU(hn::Add(hn::Add(hn::Mul(br, r), hn::Mul(bg, g)), hn::Mul(bb, b)), df, cb + i);
    hn::StoreU(hn::Add(hn::Add(hn::Mul(rr, r), hn::Mul(rg, g)), hn::Mul(rb, b)), df, cr + i);
  }
  for (; i < n; ++i) {
    const auto r = static_cast<float>(rgb[3 * i] - shift_r), g = static_cast<float>(rgb[3 * i + 1] - shift_g),
               b = static_cast<float>(rgb[3 * i + 2] - shift_b);
    y[i] = 0.299f * r + 0.587f * g + 0.114f * b;
    cb[i] = -0.16875f * r - 0.33126f * g + 0.5f * b;
    cr[i] = 0.5f * r - 0.41869f * g - 0.08131f * b;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::simd {
HWY_EXPORT(RctForwardRgb8);
HWY_EXPORT(IctForwardRgb8);

void rct_forward_rgb8_row(const std::uint8_t* rgb, std::int32_t shift_r, std::int32_t shift_g, std::int32_t shift_b,
                          std::int32_t* y, std::int32_t* cb, std::int32_t* cr, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(RctForwardRgb8)(rgb, shift_r, shift_g, shift_b, y, cb, cr, n);
}
void ict_forward_rgb8_row(const std::uint8_t* rgb, std::int32_t shift_r, std::int32_t shift_g, std::int32_t shift_b,
                          float* y, float* cb, float* cr, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(IctForwardRgb8)(rgb, shift_r, shift_g, shift_b, y, cb, cr, n);
}

}  // namespace codec::simd
#endif
