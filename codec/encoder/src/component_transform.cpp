#include "codec/encoder/component_transform.h"

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

}  // namespace codec
