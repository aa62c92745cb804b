#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

namespace codec {

// DC level shift (T.800 G.1.2): unsigned samples are centred on zero before the transform.
void dc_shift_forward(std::span<std::int32_t> samples, int precision);

// Reversible component transform (T.800 G.2.1, equations G-5 to G-7), in place on three
// equally sized components: Y = floor((R + 2G + B) / 4), Cb = B - G, Cr = R - G.
void rct_forward(std::span<std::int32_t> c0, std::span<std::int32_t> c1, std::span<std::int32_t> c2);

// Irreversible component transform (T.800 G.3.1, equation G-9), in place.
void ict_forward(std::span<float> c0, std::span<float> c1, std::span<float> c2);

// One row of each, fused with the DC level shift: out = transform(in - shift), the same values as
// dc_shift_forward then rct_forward / ict_forward (the ICT in float, each product and sum in the
// same order).
void rct_forward_row(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::int32_t shift_r,
                     std::int32_t shift_g, std::int32_t shift_b, std::int32_t* y, std::int32_t* cb, std::int32_t* cr,
                     std::size_t n);
void ict_forward_row(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::int32_t shift_r,
                     std::int32_t shift_g, std::int32_t shift_b, float* y, float* cb, float* cr, std::size_t n);

}  // namespace codec
