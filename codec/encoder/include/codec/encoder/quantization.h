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

// The same, also returning what the index drops: floor(256 * (|c| / delta - |index|)), for tier-1
// to measure distortion against the coefficient rather than the index (t1::encode_block).
inline std::int32_t quantize(float coefficient, float inverse_delta, std::uint8_t& fraction) {
  const float m = (coefficient < 0 ? -coefficient : coefficient) * inverse_delta;
  const auto q = static_cast<std::int32_t>(m);
  const auto f = static_cast<int>((m - static_cast<float>(q)) * 256.0f);
  fraction = static_cast<std::uint8_t>(f < 0 ? 0 : f > 255 ? 255 : f);
  return coefficient < 0 ? -q : q;
}

}  // namespace codec
