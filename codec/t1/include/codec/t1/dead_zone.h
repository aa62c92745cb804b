#pragma once
#include <cstdint>

namespace codec::t1 {

// Scalar dead-zone quantisation (T.800 E.1.1): sign(c) * floor(|c| / delta), given 1 / delta.
// Magnitudes are held below 2^31 (the largest float under it), which no legal Mb exceeds anyway:
// the guard-bit check then refuses the tile instead of an overflowing conversion.
inline constexpr float kLargestMagnitude = 2147483520.0f;

inline float scaled_magnitude(float coefficient, float inverse_delta) {
  const float m = (coefficient < 0 ? -coefficient : coefficient) * inverse_delta;
  return m < kLargestMagnitude ? m : kLargestMagnitude;
}

inline std::int32_t quantize(float coefficient, float inverse_delta) {
  const auto q = static_cast<std::int32_t>(scaled_magnitude(coefficient, inverse_delta));
  return coefficient < 0 ? -q : q;
}

// The same, also returning what the index drops: floor(256 * (|c| / delta - |index|)), for tier-1
// to measure distortion against the coefficient rather than the index (encode_block).
inline std::int32_t quantize(float coefficient, float inverse_delta, std::uint8_t& fraction) {
  const float m = scaled_magnitude(coefficient, inverse_delta);
  const auto q = static_cast<std::int32_t>(m);
  const auto f = static_cast<int>((m - static_cast<float>(q)) * 256.0f);
  fraction = static_cast<std::uint8_t>(f < 0 ? 0 : f > 255 ? 255 : f);
  return coefficient < 0 ? -q : q;
}

}  // namespace codec::t1
