// Highway's foreach_target re-includes this file once per SIMD target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/lifting_simd.cpp"
#include <hwy/foreach_target.h>  // must precede highway.h
#include <hwy/highway.h>

#include "lifting_simd.h"

HWY_BEFORE_NAMESPACE();
namespace dwt_cpu::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void LiftSymmetric(float* HWY_RESTRICT t, const float* HWY_RESTRICT l, const float* HWY_RESTRICT r, float c,
                   std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  const auto vc = hn::Set(d, c);
  std::size_t i = 0;
  for (; i + N <= n; i += N)
    hn::StoreU(hn::MulAdd(vc, hn::Add(hn::LoadU(d, l + i), hn::LoadU(d, r + i)), hn::LoadU(d, t + i)), d, t + i);
  for (; i < n; ++i) t[i] += c * (l[i] + r[i]);
}

void LiftGeneral(float* HWY_RESTRICT t, const float* HWY_RESTRICT l, const float* HWY_RESTRICT r, float cl, float cr,
                 std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  const auto vl = hn::Set(d, cl), vr = hn::Set(d, cr);
  std::size_t i = 0;
  for (; i + N <= n; i += N) {
    auto v = hn::MulAdd(vl, hn::LoadU(d, l + i), hn::LoadU(d, t + i));
    hn::StoreU(hn::MulAdd(vr, hn::LoadU(d, r + i), v), d, t + i);
  }
  for (; i < n; ++i) t[i] += cl * l[i] + cr * r[i];
}

void Scale(float* HWY_RESTRICT t, float s, std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  const auto vs = hn::Set(d, s);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(hn::Mul(hn::LoadU(d, t + i), vs), d, t + i);
  for (; i < n; ++i) t[i] *= s;
}

void ScaleCopy(const float* HWY_RESTRICT src, float* HWY_RESTRICT dst, float s, std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  const auto vs = hn::Set(d, s);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(hn::Mul(hn::LoadU(d, src + i), vs), d, dst + i);
  for (; i < n; ++i) dst[i] = src[i] * s;
}

void Predict53(std::int32_t* HWY_RESTRICT t, const std::int32_t* HWY_RESTRICT l, const std::int32_t* HWY_RESTRICT r,
               std::size_t n, bool inverse) {
  const hn::ScalableTag<std::int32_t> d;
  const std::size_t N = hn::Lanes(d);
  std::size_t i = 0;
  // Arithmetic shift right is floor division for negative sums too, as T.800 requires.
  if (inverse) {
    for (; i + N <= n; i += N)
      hn::StoreU(hn::Add(hn::LoadU(d, t + i), hn::ShiftRight<1>(hn::Add(hn::LoadU(d, l + i), hn::LoadU(d, r + i)))), d,
                 t + i);
    for (; i < n; ++i) t[i] += (l[i] + r[i]) >> 1;
  } else {
    for (; i + N <= n; i += N)
      hn::StoreU(hn::Sub(hn::LoadU(d, t + i), hn::ShiftRight<1>(hn::Add(hn::LoadU(d, l + i), hn::LoadU(d, r + i)))), d,
                 t + i);
    for (; i < n; ++i) t[i] -= (l[i] + r[i]) >> 1;
  }
}

void Update53(std::int32_t* HWY_RESTRICT t, const std::int32_t* HWY_RESTRICT l, const std::int32_t* HWY_RESTRICT r,
              std::size_t n, bool inverse) {
  const hn::ScalableTag<std::int32_t> d;
  const std::size_t N = hn::Lanes(d);
  const auto two = hn::Set(d, 2);
  std::size_t i = 0;
  if (inverse) {
    for (; i + N <= n; i += N)
      hn::StoreU(hn::Sub(hn::LoadU(d, t + i),
                         hn::ShiftRight<2>(hn::Add(hn::Add(hn::LoadU(d, l + i), hn::LoadU(d, r + i)), two))),
                 d, t + i);
    for (; i < n; ++i) t[i] -= (l[i] + r[i] + 2) >> 2;
  } else {
    for (; i + N <= n; i += N)
      hn::StoreU(hn::Add(hn::LoadU(d, t + i),
                         hn::ShiftRight<2>(hn::Add(hn::Add(hn::LoadU(d, l + i), hn::LoadU(d, r + i)), two))),
                 d, t + i);
    for (; i < n; ++i) t[i] += (l[i] + r[i] + 2) >> 2;
  }
}

// Line kernels: the per-line operations above over every other line of a strip.
template <class T, class Op>
HWY_INLINE void ForTargetLines(T* HWY_RESTRICT data, std::size_t stride, int first, int end, Op op) {
  for (int b = first; b + 1 < end; b += 2) {
    T* line = data + static_cast<std::size_t>(b) * stride;
    op(line, line - stride, line + stride);
  }
}
void LiftLinesSymmetric(float* data, std::size_t stride, std::size_t lanes, int first, int end, float c) {
  ForTargetLines(data, stride, first, end,
                 [&](float* t, const float* l, const float* r) { LiftSymmetric(t, l, r, c, lanes); });
}
void LiftLinesGeneral(float* data, std::size_t stride, std::size_t lanes, int first, int end, float cl, float cr) {
  ForTargetLines(data, stride, first, end,
                 [&](float* t, const float* l, const float* r) { LiftGeneral(t, l, r, cl, cr, lanes); });
}
void Predict53Lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse) {
  ForTargetLines(data, stride, first, end, [&](std::int32_t* t, const std::int32_t* l, const std::int32_t* r) {
    Predict53(t, l, r, lanes, inverse);
  });
}
void Update53Lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse) {
  ForTargetLines(data, stride, first, end, [&](std::int32_t* t, const std::int32_t* l, const std::int32_t* r) {
    Update53(t, l, r, lanes, inverse);
  });
}

template <class T>
void DeinterleaveImpl(const T* HWY_RESTRICT src, T* HWY_RESTRICT even, T* HWY_RESTRICT odd, std::size_t n) {
  const hn::ScalableTag<T> d;
  const std::size_t N = hn::Lanes(d);
  std::size_t j = 0;
  for (; j + N <= n; j += N) {
    hn::Vec<decltype(d)> e, o;
    hn::LoadInterleaved2(d, src + 2 * j, e, o);
    hn::StoreU(e, d, even + j);
    hn::StoreU(o, d, odd + j);
  }
  for (; j < n; ++j) even[j] = src[2 * j], odd[j] = src[2 * j + 1];
}
void DeinterleaveFloat(const float* src, float* even, float* odd, std::size_t n) {
  DeinterleaveImpl(src, even, odd, n);
}
void DeinterleaveInt(const std::int32_t* src, std::int32_t* even, std::int32_t* odd, std::size_t n) {
  DeinterleaveImpl(src, even, odd, n);
}

template <class T>
void InterleaveImpl(const T* HWY_RESTRICT even, const T* HWY_RESTRICT odd, T* HWY_RESTRICT dst, std::size_t n) {
  const hn::ScalableTag<T> d;
  const std::size_t N = hn::Lanes(d);
  std::size_t j = 0;
  for (; j + N <= n; j += N) hn::StoreInterleaved2(hn::LoadU(d, even + j), hn::LoadU(d, odd + j), d, dst + 2 * j);
  for (; j < n; ++j) dst[2 * j] = even[j], dst[2 * j + 1] = odd[j];
}
void InterleaveFloat(const float* even, const float* odd, float* dst, std::size_t n) {
  InterleaveImpl(even, odd, dst, n);
}
void InterleaveInt(const std::int32_t* even, const std::int32_t* odd, std::int32_t* dst, std::size_t n) {
  InterleaveImpl(even, odd, dst, n);
}

std::int64_t CurrentTarget() { return HWY_TARGET; }

}  // namespace HWY_NAMESPACE
}  // namespace dwt_cpu::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace dwt_cpu::simd {
HWY_EXPORT(LiftSymmetric);
HWY_EXPORT(LiftGeneral);
HWY_EXPORT(Scale);
HWY_EXPORT(ScaleCopy);
HWY_EXPORT(Predict53);
HWY_EXPORT(Update53);
HWY_EXPORT(LiftLinesSymmetric);
HWY_EXPORT(LiftLinesGeneral);
HWY_EXPORT(Predict53Lines);
HWY_EXPORT(Update53Lines);
HWY_EXPORT(DeinterleaveFloat);
HWY_EXPORT(DeinterleaveInt);
HWY_EXPORT(InterleaveFloat);
HWY_EXPORT(InterleaveInt);
HWY_EXPORT(CurrentTarget);

void lift_symmetric(float* t, const float* l, const float* r, float c, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(LiftSymmetric)(t, l, r, c, n);
}
void lift_general(float* t, const float* l, const float* r, float cl, float cr, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(LiftGeneral)(t, l, r, cl, cr, n);
}
void scale(float* t, float s, std::size_t n) { HWY_DYNAMIC_DISPATCH(Scale)(t, s, n); }
void scale_copy(const float* src, float* dst, float s, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(ScaleCopy)(src, dst, s, n);
}
void predict53(std::int32_t* t, const std::int32_t* l, const std::int32_t* r, std::size_t n, bool inverse) {
  HWY_DYNAMIC_DISPATCH(Predict53)(t, l, r, n, inverse);
}
void update53(std::int32_t* t, const std::int32_t* l, const std::int32_t* r, std::size_t n, bool inverse) {
  HWY_DYNAMIC_DISPATCH(Update53)(t, l, r, n, inverse);
}
void lift_lines_symmetric(float* data, std::size_t stride, std::size_t lanes, int first, int end, float c) {
  HWY_DYNAMIC_DISPATCH(LiftLinesSymmetric)(data, stride, lanes, first, end, c);
}
void lift_lines_general(float* data, std::size_t stride, std::size_t lanes, int first, int end, float cl, float cr) {
  HWY_DYNAMIC_DISPATCH(LiftLinesGeneral)(data, stride, lanes, first, end, cl, cr);
}
void predict53_lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse) {
  HWY_DYNAMIC_DISPATCH(Predict53Lines)(data, stride, lanes, first, end, inverse);
}
void update53_lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse) {
  HWY_DYNAMIC_DISPATCH(Update53Lines)(data, stride, lanes, first, end, inverse);
}
void deinterleave(const float* src, float* even, float* odd, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(DeinterleaveFloat)(src, even, odd, n);
}
void deinterleave(const std::int32_t* src, std::int32_t* even, std::int32_t* odd, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(DeinterleaveInt)(src, even, odd, n);
}
void interleave(const float* even, const float* odd, float* dst, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(InterleaveFloat)(even, odd, dst, n);
}
void interleave(const std::int32_t* even, const std::int32_t* odd, std::int32_t* dst, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(InterleaveInt)(even, odd, dst, n);
}
const char* target_name() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(CurrentTarget)()); }

}  // namespace dwt_cpu::simd
#endif
