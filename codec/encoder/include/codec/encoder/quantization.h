#pragma once
#include <cstdint>

namespace codec {

// A quantisation step as QCD/QCC carry it (T.800 E.1, equation E-3):
// delta = 2^(R - exponent) * (1 + mantissa / 2^11), R being the band's nominal dynamic range in bits.
struct StepSize {
  int exponent = 0;  // 0..31
  int mantissa = 0;  // 0..2047
};

// The representable step nearest below-or-at `delta` (never coarser than asked), for range R.
StepSize encode_step(double delta, int range_bits);
double step_value(StepSize step, int range_bits);

// Scalar dead-zone quantisation (T.800 E.1.1): sign(c) * floor(|c| / delta).
inline std::int32_t quantize(float coefficient, float inverse_delta) {
  const float m = (coefficient < 0 ? -coefficient : coefficient) * inverse_delta;
  const auto q = static_cast<std::int32_t>(m);
  return coefficient < 0 ? -q : q;
}

}  // namespace codec
