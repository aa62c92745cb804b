// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/column_masks_simd.cpp"
#include <hwy/foreach_target.h>  // must precede highway.h
#include <hwy/highway.h>

#include <cstring>

#include "column_masks_simd.h"

HWY_BEFORE_NAMESPACE();
namespace codec::t1::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The mask's lanes as the low bits of a word.
template <class D>
HWY_INLINE std::uint64_t MaskBits(D d, hn::Mask<D> mask) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  return bits;
}

std::uint64_t ColumnsWith(const std::uint32_t* HWY_RESTRICT words, std::size_t n, std::uint32_t bits) {
  const hn::ScalableTag<std::uint32_t> du;
  const std::size_t N = hn::Lanes(du);
  const auto wanted = hn::Set(du, bits);
  std::uint64_t out = 0;
  std::size_t i = 0;
  for (; i + N <= n; i += N) out |= MaskBits(du, hn::Ne(hn::And(hn::LoadU(du, words + i), wanted), hn::Zero(du))) << i;
  for (; i < n; ++i) out |= static_cast<std::uint64_t>((words[i] & bits) != 0) << i;
  return out;
}

std::uint64_t QuietColumns(const std::uint32_t* HWY_RESTRICT words, const std::uint32_t* HWY_RESTRICT magnitudes,
                           std::size_t n, std::uint32_t bits, int plane) {
  const hn::ScalableTag<std::uint32_t> du;
  const std::size_t N = hn::Lanes(du);
  const auto wanted = hn::Set(du, bits);
  std::uint64_t out = 0;
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto busy =
        hn::Or(hn::And(hn::LoadU(du, words + i), wanted), hn::ShiftRightSame(hn::LoadU(du, magnitudes + i), plane));
    out |= MaskBits(du, hn::Eq(busy, hn::Zero(du))) << i;
  }
  for (; i < n; ++i) out |= static_cast<std::uint64_t>(((words[i] & bits) | (magnitudes[i] >> plane)) == 0) << i;
  return out;
}

}  // namespace HWY_NAMESPACE
}  // namespace codec::t1::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace codec::t1::simd {
HWY_EXPORT(ColumnsWith);
HWY_EXPORT(QuietColumns);

std::uint64_t columns_with(const std::uint32_t* words, std::size_t n, std::uint32_t bits) {
  return HWY_DYNAMIC_DISPATCH(ColumnsWith)(words, n, bits);
}

std::uint64_t quiet_columns(const std::uint32_t* words, const std::uint32_t* magnitudes, std::size_t n,
                            std::uint32_t bits, int plane) {
  return HWY_DYNAMIC_DISPATCH(QuietColumns)(words, magnitudes, n, bits, plane);
}

}  // namespace codec::t1::simd
#endif
