#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// Sqcd's low five bits (T.800 Table A.28).
enum class QuantizationStyle : std::uint8_t { None = 0, ScalarDerived = 1, ScalarExpounded = 2 };

// One subband's step size, Delta_b = 2^-exponent * (1 + mantissa / 2^11) relative to the band's
// dynamic range (T.800 E.1.1). With QuantizationStyle::None only the exponent is signalled.
struct StepSize {
  unsigned exponent = 0;  // 0..31
  unsigned mantissa = 0;  // 0..2047; must be 0 for QuantizationStyle::None
};

// Sqcd + SPqcd (T.800 A.6.4), shared by QCD and QCC.
//
// steps holds, for None and ScalarExpounded, one entry per subband in the order LL, then HL, LH,
// HH of each decomposition level from the coarsest to the finest: 3 * levels + 1 entries (see
// subband_slot). For ScalarDerived it holds one entry, LL's; the decoder derives the others.
struct Quantization {
  unsigned guard_bits = 2;  // 0..7, Sqcd bits 5-7
  QuantizationStyle style = QuantizationStyle::None;
  std::vector<StepSize> steps;
};

// Quantization component (T.800 A.6.5): overrides the QCD for one component.
struct Qcc {
  unsigned component = 0;
  Quantization quant;
};

enum class SubbandOrientation { LL, HL, LH, HH };

// 3 * levels + 1: the number of subbands of a tile-component with `levels` decompositions.
std::size_t subband_count(unsigned levels);

// Index into Quantization::steps of a subband. `level` counts decompositions from the finest
// (1) to the coarsest (`levels`), as in T.800 Annex F; LL is only at level == levels (or
// levels == 0). Throws CodestreamError for a band that does not exist.
std::size_t subband_slot(unsigned levels, unsigned level, SubbandOrientation orientation);

// Throws CodestreamError unless the fields are in range and the number of steps fits the style
// (1 for derived; 3n + 1 <= 97 otherwise). Whether it matches the component's level count is
// checked where both are known (validate_main_header).
void validate_quantization(const Quantization& q, const char* who);

// validate_quantization plus the component index against Csiz.
void validate_qcc(const Qcc& qcc, unsigned num_components);

// Lqcd = 3 + n (None: 1 byte per band, exponent << 3) or 3 + 2n (scalar: u16 exponent << 11 | mantissa).
void write_qcd(ByteWriter& out, const Quantization& q);

// Cqcc is one byte when Csiz < 257, two otherwise (Table A.31).
void write_qcc(ByteWriter& out, const Qcc& qcc, unsigned num_components);

}  // namespace codec::cs
