#include "component_transform.h"

namespace codec {

void dc_shift_forward(std::span<std::int32_t> samples, int precision) {
  const std::int32_t shift = std::int32_t{1} << (precision - 1);
  for (auto& v : samples) v -= shift;
}

void rct_forward(std::span<std::int32_t> c0, std::span<std::int32_t> c1, std::span<std::int32_t> c2) {
  for (std::size_t i = 0; i < c0.size(); ++i) {
    const std::int32_t r = c0[i], g = c1[i], b = c2[i];
    c0[i] = (r + 2 * g + b) >> 2;  // arithmetic shift: floor, as G-5 requires for negative sums
    c1[i] = b - g;
    c2[i] = r - g;
  }
}

void ict_forward(std::span<float> c0, std::span<float> c1, std::span<float> c2) {
  for (std::size_t i = 0; i < c0.size(); ++i) {
    const float r = c0[i], g = c1[i], b = c2[i];
    c0[i] = 0.299f * r + 0.587f * g + 0.114f * b;
    c1[i] = -0.16875f * r - 0.33126f * g + 0.5f * b;
    c2[i] = 0.5f * r - 0.41869f * g - 0.08131f * b;
  }
}

void rct_forward_row(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::int32_t shift_r,
                     std::int32_t shift_g, std::int32_t shift_b, std::int32_t* y, std::int32_t* cb, std::int32_t* cr,
                     std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t rr = r[i] - shift_r, gg = g[i] - shift_g, bb = b[i] - shift_b;
    y[i] = (rr + 2 * gg + bb) >> 2;
    cb[i] = bb - gg;
    cr[i] = rr - gg;
  }
}

void ict_forward_row(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::int32_t shift_r,
                     std::int32_t shift_g, std::int32_t shift_b, float* y, float* cb, float* cr, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const auto rr = static_cast<float>(r[i] - shift_r), gg = static_cast<float>(g[i] - shift_g),
               bb = static_cast<float>(b[i] - shift_b);
    y[i] = 0.299f * rr + 0.587f * gg + 0.114f * bb;
    cb[i] = -0.16875f * rr - 0.33126f * gg + 0.5f * bb;
    cr[i] = 0.5f * rr - 0.41869f * gg - 0.08131f * bb;
  }
}

}  // namespace codec
