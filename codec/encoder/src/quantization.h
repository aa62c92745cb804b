#pragma once
#include <cstdint>

#include "codec/t1/dead_zone.h"

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

// Dead-zone quantisation itself lives with tier-1, which quantises code-blocks as it loads them.
using t1::quantize;

}  // namespace codec
