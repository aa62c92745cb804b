#pragma once
#include <cstddef>
#include <cstdint>

// Element-wise lifting operations over the lanes of strip lines. Each call combines one target
// line with its two neighbouring lines; lanes are independent rows (horizontal pass) or columns
// (vertical pass). Dispatched at run time to the best SIMD target Highway finds.
namespace dwt_cpu::simd {

// t += c * (l + r)
void lift_symmetric(float* t, const float* l, const float* r, float c, std::size_t n);
// t += cl * l + cr * r
void lift_general(float* t, const float* l, const float* r, float cl, float cr, std::size_t n);
// t *= s
void scale(float* t, float s, std::size_t n);
// Reversible 5/3 (T.800 F.4.8.1): predict t -= floor((l + r) / 2); update t += floor((l + r + 2) / 4).
// `inverse` undoes the step exactly.
void predict53(std::int32_t* t, const std::int32_t* l, const std::int32_t* r, std::size_t n, bool inverse);
void update53(std::int32_t* t, const std::int32_t* l, const std::int32_t* r, std::size_t n, bool inverse);

// The same over every other line of a strip, one call per lifting step (a call per line costs a
// dispatch per 64 lanes): for b = first, first + 2, ... with b + 1 < end, line b (lines `stride`
// apart, `lanes` long) is the target and lines b - 1 and b + 1 its neighbours.
void lift_lines_symmetric(float* data, std::size_t stride, std::size_t lanes, int first, int end, float c);
void lift_lines_general(float* data, std::size_t stride, std::size_t lanes, int first, int end, float cl, float cr);
void predict53_lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse);
void update53_lines(std::int32_t* data, std::size_t stride, std::size_t lanes, int first, int end, bool inverse);

// dst = s * src (the gains applied as a strip's lines are copied out).
void scale_copy(const float* src, float* dst, float s, std::size_t n);

// Splits n interleaved pairs: even[j] = src[2j], odd[j] = src[2j + 1].
void deinterleave(const float* src, float* even, float* odd, std::size_t n);
void deinterleave(const std::int32_t* src, std::int32_t* even, std::int32_t* odd, std::size_t n);
// Joins n pairs, deinterleave's inverse: dst[2j] = even[j], dst[2j + 1] = odd[j].
void interleave(const float* even, const float* odd, float* dst, std::size_t n);
void interleave(const std::int32_t* even, const std::int32_t* odd, std::int32_t* dst, std::size_t n);

const char* target_name();  // e.g. "AVX2"

}  // namespace dwt_cpu::simd
