// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "plane_error_simd.cpp"  // found through the src include directory
#include <hwy/foreach_target.h>                    // must precede highway.h
#include <hwy/highway.h>

#include "plane_error_simd.h"

HWY_BEFORE_NAMESPACE();
namespace codec::ht::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void AddSignificantErrors(const std::uint32_t* HWY_RESTRICT magnitude, const double* HWY_RESTRICT offset, std::size_t n,
                          int planes, double half_at_zero, double* HWY_RESTRICT error) {
  const hn::ScalableTag<double> dd;
  const hn::Rebind<std::int32_t, decltype(dd)> di;  // as many int32 lanes as doubles
  const std::size_t N = hn::Lanes(dd);
  for (int p = 0; p < planes; ++p) {
    const auto low_bits = static_cast<std::int32_t>((std::uint32_t{1} << p) - 1);
    const double half = p > 0 ? static_cast<double>(std::uint32_t{1} << (p - 1)) : half_at_zero;
    const auto mask = hn::Set(di, low_bits), one = hn::Set(di, 1);
    const auto h = hn::Set(dd, half);
    auto sum = hn::Zero(dd);
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
      // Magnitudes are below 2^31, so they compare and mask as int32.
      const auto m = hn::BitCast(di, hn::LoadU(hn::RebindToUnsigned<decltype(di)>(), magnitude + i));
      const auto significant = hn::PromoteTo(dd, hn::IfThenElseZero(hn::Gt(m, mask), one));  // 1.0 or 0.0
      const auto residual = hn::Sub(hn::Add(hn::PromoteTo(dd, hn::And(m, mask)), hn::LoadU(dd, offset + i)), h);
      const auto counted = hn::Mul(residual, significant);
      sum = hn::MulAdd(counted, counted, sum);
    }
    double total = hn::GetLane(hn::SumOfLanes(dd, sum));
    for (; i < n; ++i) {
      if (magnitude[i] <= static_cast<std::uint32_t>(low_bits)) continue;
      const double residual =
          static_cast<double>(magnitude[i] & static_cast<std::uint32_t>(low_bits)) + offset[i] - half;
      total += residual * residual;
    }
    error[p] += total;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::ht::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::ht::simd {
HWY_EXPORT(AddSignificantErrors);

void add_significant_errors(const std::uint32_t* magnitude, const double* offset, std::size_t n, int planes,
                            double half_at_zero, double* error) {
  HWY_DYNAMIC_DISPATCH(AddSignificantErrors)(magnitude, offset, n, planes, half_at_zero, error);
}

}  // namespace codec::ht::simd
#endif
