// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "pnm_interleave.cpp"  // found through the src include directory
#include <hwy/foreach_target.h>                  // must precede highway.h
#include <hwy/highway.h>

#include <algorithm>

#include "pnm_interleave.h"

HWY_BEFORE_NAMESPACE();
namespace imageio::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The samples as unsigned lanes (for the largest) and as bytes; a sample outside 0..255 is
// truncated to its low byte, as the scalar tail does (the caller refuses the raster then).
template <class DI>
HWY_INLINE hn::Vec<hn::Rebind<std::uint8_t, DI>> LowBytes(DI di, hn::Vec<DI> v,
                                                          hn::Vec<hn::RebindToUnsigned<DI>>& largest) {
  largest = hn::Max(largest, hn::BitCast(hn::RebindToUnsigned<DI>(), v));
  return hn::DemoteTo(hn::Rebind<std::uint8_t, DI>(), hn::And(v, hn::Set(di, 0xFF)));
}

std::uint32_t InterleaveRgb8(const std::int32_t* HWY_RESTRICT r, const std::int32_t* HWY_RESTRICT g,
                             const std::int32_t* HWY_RESTRICT b, std::uint8_t* HWY_RESTRICT out, std::size_t n) {
  const hn::ScalableTag<std::int32_t> di;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t N = hn::Lanes(di);
  auto largest = hn::Zero(hn::RebindToUnsigned<decltype(di)>());
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    const auto r8 = LowBytes(di, hn::LoadU(di, r + i), largest);
    const auto g8 = LowBytes(di, hn::LoadU(di, g + i), largest);
    const auto b8 = LowBytes(di, hn::LoadU(di, b + i), largest);
    hn::StoreInterleaved3(r8, g8, b8, d8, out + 3 * i);
  }
  std::uint32_t most = hn::GetLane(hn::MaxOfLanes(hn::RebindToUnsigned<decltype(di)>(), largest));
  for (; i < n; ++i) {
    const std::int32_t rgb[3] = {r[i], g[i], b[i]};
    for (int c = 0; c < 3; ++c) {
      most = std::max(most, static_cast<std::uint32_t>(rgb[c]));
      out[3 * i + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(rgb[c]);
    }
  }
  return most;
}

std::uint32_t InterleaveGrey8(const std::int32_t* HWY_RESTRICT grey, std::uint8_t* HWY_RESTRICT out, std::size_t n) {
  const hn::ScalableTag<std::int32_t> di;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;
  const std::size_t N = hn::Lanes(di);
  auto largest = hn::Zero(hn::RebindToUnsigned<decltype(di)>());
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(LowBytes(di, hn::LoadU(di, grey + i), largest), d8, out + i);
  std::uint32_t most = hn::GetLane(hn::MaxOfLanes(hn::RebindToUnsigned<decltype(di)>(), largest));
  for (; i < n; ++i) {
    most = std::max(most, static_cast<std::uint32_t>(grey[i]));
    out[i] = static_cast<std::uint8_t>(grey[i]);
  }
  return most;
}

}  // namespace HWY_NAMESPACE
}  // namespace imageio::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace imageio::detail {
HWY_EXPORT(InterleaveRgb8);
HWY_EXPORT(InterleaveGrey8);

std::uint32_t interleave_rgb8(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::uint8_t* out,
                              std::size_t n) {
  return HWY_DYNAMIC_DISPATCH(InterleaveRgb8)(r, g, b, out, n);
}

std::uint32_t interleave_grey8(const std::int32_t* grey, std::uint8_t* out, std::size_t n) {
  return HWY_DYNAMIC_DISPATCH(InterleaveGrey8)(grey, out, n);
}

namespace {
// Samples of more than 8 bits, less common (and twice the bytes to write anyway): scalar.
template <std::size_t Channels>
std::uint32_t interleave16(const std::int32_t* const (&planes)[Channels], std::uint8_t* out, std::size_t n) {
  std::uint32_t most = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < Channels; ++c) {
      const auto v = static_cast<std::uint32_t>(planes[c][i]);
      most = std::max(most, v);
      out[2 * (i * Channels + c)] = static_cast<std::uint8_t>(v >> 8);  // big-endian
      out[2 * (i * Channels + c) + 1] = static_cast<std::uint8_t>(v);
    }
  return most;
}
}  // namespace

std::uint32_t interleave_rgb16(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::uint8_t* out,
                               std::size_t n) {
  const std::int32_t* const planes[3] = {r, g, b};
  return interleave16<3>(planes, out, n);
}

std::uint32_t interleave_grey16(const std::int32_t* grey, std::uint8_t* out, std::size_t n) {
  const std::int32_t* const planes[1] = {grey};
  return interleave16<1>(planes, out, n);
}

}  // namespace imageio::detail
#endif
