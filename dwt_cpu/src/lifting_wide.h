#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>

// lifting_simd.h's operations on 64-bit lanes: the reversible 5/3 on int64 planes and the float
// kernels on double planes, for samples of more than 31 bits (T.800 allows 38, plus the DWT's
// growth) where int32 would overflow and float would round away their low bits. Plain loops the
// compiler vectorises where it can: such planes are rare and their speed matters less than
// their exactness. The same names as lifting_simd.h, so that the templated passes pick them by
// overload.
namespace dwt_cpu::simd {

template <class T>
concept WideLane = std::is_same_v<T, std::int64_t> || std::is_same_v<T, double>;

inline void lift_symmetric(double* t, const double* l, const double* r, double c, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) t[i] += c * (l[i] + r[i]);
}
inline void lift_general(double* t, const double* l, const double* r, double cl, double cr, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) t[i] += cl * l[i] + cr * r[i];
}
inline void scale(double* t, double s, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) t[i] *= s;
}
inline void scale_copy(const double* src, double* dst, double s, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) dst[i] = src[i] * s;
}
// Two's complement sums, as the int32 vector lanes wrap: a hostile stream's coefficients may
// overflow, and must not be undefined behaviour (the decoder clamps what comes out).
inline std::int64_t wrapping_add(std::int64_t a, std::int64_t b) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
}
inline std::int64_t wrapping_sub(std::int64_t a, std::int64_t b) {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
}

// T.800 F.4.8.1, as predict53 / update53: the arithmetic shift is floor division.
inline void predict53(std::int64_t* t, const std::int64_t* l, const std::int64_t* r, std::size_t n, bool inverse) {
  if (inverse)
    for (std::size_t i = 0; i < n; ++i) t[i] = wrapping_add(t[i], wrapping_add(l[i], r[i]) >> 1);
  else
    for (std::size_t i = 0; i < n; ++i) t[i] = wrapping_sub(t[i], wrapping_add(l[i], r[i]) >> 1);
}
inline void update53(std::int64_t* t, const std::int64_t* l, const std::int64_t* r, std::size_t n, bool inverse) {
  if (inverse)
    for (std::size_t i = 0; i < n; ++i) t[i] = wrapping_sub(t[i], wrapping_add(wrapping_add(l[i], r[i]), 2) >> 2);
  else
    for (std::size_t i = 0; i < n; ++i) t[i] = wrapping_add(t[i], wrapping_add(wrapping_add(l[i], r[i]), 2) >> 2);
}

// Every other line of a strip, as the *_lines operations of lifting_simd.h.
template <class T, class Op>
void for_target_lines(T* data, std::size_t stride, int first, int end, Op op) {
  for (int b = first; b + 1 < end; b += 2) {
    T* line = data + static_cast<std::size_t>(b) * stride;
    op(line, line - stride, line + stride);
  }
}
inline void lift_lines_symmetric(double* data, std::size_t stride, std::size_t lanes, int first, int end, double c) {
  for_target_lines(data, stride, first, end,
                   [&](double* t, const double* l, const double* r) { lift_symmetric(t, l, r, c, lanes); });
}
inline void lift_lines_general(double* data, std::size_t stride, std::size_t lanes, int first, int end, double cl,
                               double cr) {
  for_target_lines(data, stride, first, end,
                   [&](double* t, const double* l, const double* r) { lift_general(t, l, r, cl, cr, lanes); });
}
inline void predict53_lines(std::int64_t* data, std::size_t stride, std::size_t lanes, int first, int end,
                            bool inverse) {
  for_target_lines(data, stride, first, end, [&](std::int64_t* t, const std::int64_t* l, const std::int64_t* r) {
    predict53(t, l, r, lanes, inverse);
  });
}
inline void update53_lines(std::int64_t* data, std::size_t stride, std::size_t lanes, int first, int end,
                           bool inverse) {
  for_target_lines(data, stride, first, end, [&](std::int64_t* t, const std::int64_t* l, const std::int64_t* r) {
    update53(t, l, r, lanes, inverse);
  });
}

template <WideLane T>
void deinterleave(const T* src, T* even, T* odd, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) even[j] = src[2 * j], odd[j] = src[2 * j + 1];
}
template <WideLane T>
void interleave(const T* even, const T* odd, T* dst, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) dst[2 * j] = even[j], dst[2 * j + 1] = odd[j];
}

}  // namespace dwt_cpu::simd
