#include "quantization.h"

#include <cmath>

#include "codec/structure/error.h"

namespace codec {

StepSize encode_step(double delta, int range_bits) {
  if (!(delta > 0) || !std::isfinite(delta)) throw EncodeError("quantisation step must be positive");
  // delta / 2^R = 2^-exponent * (1 + mantissa / 2048) with the bracket in [1, 2).
  const double x = delta / std::ldexp(1.0, range_bits);
  int exponent = -static_cast<int>(std::floor(std::log2(x)));
  double fraction = x * std::ldexp(1.0, exponent);  // in [1, 2) up to rounding
  if (fraction >= 2.0) {
    fraction /= 2.0;
    --exponent;
  } else if (fraction < 1.0) {
    fraction *= 2.0;
    ++exponent;
  }
  // Round the mantissa down so the written step is never coarser than the one asked for.
  int mantissa = static_cast<int>(std::floor((fraction - 1.0) * 2048.0));
  if (mantissa > 2047) mantissa = 2047;
  if (exponent < 0) return StepSize{0, 2047};  // coarsest representable
  if (exponent > 31) throw EncodeError("quantisation step too fine to signal (exponent over 31)");
  return StepSize{exponent, mantissa};
}

double step_value(StepSize s, int range_bits) { return std::ldexp(1.0 + s.mantissa / 2048.0, range_bits - s.exponent); }

}  // namespace codec
