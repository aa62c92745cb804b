#include "codec/codestream/qcd.h"

#include <string>

#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"
#include "fail.h"

namespace codec::cs {
namespace {

constexpr std::size_t kMaxSubbands = 3 * 32 + 1;  // 32 decomposition levels at most (Table A.15)

// Sqcd then SPqcd; the same bytes follow Cqcc in a QCC (Tables A.28 to A.30).
void write_sqcx_spqcx(ByteWriter& out, const Quantization& q) {
  out.u8(static_cast<std::uint8_t>((q.guard_bits << 5) | static_cast<unsigned>(q.style)));
  for (const StepSize& s : q.steps) {
    if (q.style == QuantizationStyle::None)
      out.u8(static_cast<std::uint8_t>(s.exponent << 3));
    else
      out.u16(static_cast<std::uint16_t>((s.exponent << 11) | s.mantissa));
  }
}

}  // namespace

std::size_t subband_count(unsigned levels) { return 3 * static_cast<std::size_t>(levels) + 1; }

std::size_t subband_slot(unsigned levels, unsigned level, SubbandOrientation orientation) {
  if (orientation == SubbandOrientation::LL) {
    if (level != levels)
      throw CodestreamError("subband_slot: LL exists only at the coarsest level " + std::to_string(levels));
    return 0;
  }
  if (level < 1 || level > levels)
    throw CodestreamError("subband_slot: level " + std::to_string(level) + " is outside 1.." + std::to_string(levels));
  // Coarsest level first, HL LH HH within a level (T.800 A.6.4).
  return 1 + 3 * static_cast<std::size_t>(levels - level) + (static_cast<std::size_t>(orientation) - 1);
}

void validate_quantization(const Quantization& q, const char* who) {
  if (q.guard_bits > 7) fail(who, std::to_string(q.guard_bits) + " guard bits; at most 7 fit Sqcd");
  const std::size_t n = q.steps.size();
  switch (q.style) {
    case QuantizationStyle::ScalarDerived:
      if (n != 1) fail(who, "scalar derived quantization takes exactly one step size (LL), got " + std::to_string(n));
      break;
    case QuantizationStyle::None:
    case QuantizationStyle::ScalarExpounded:
      if (n < 1 || n > kMaxSubbands || (n - 1) % 3 != 0)
        fail(who, std::to_string(n) + " step sizes; need 3 * levels + 1 with at most 32 levels");
      break;
    default:
      fail(who, "quantization style " + std::to_string(static_cast<unsigned>(q.style)) + " is not 0, 1 or 2");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const StepSize& s = q.steps[i];
    if (s.exponent > 31)
      fail(who, "subband " + std::to_string(i) + " exponent " + std::to_string(s.exponent) + " exceeds 31");
    if (s.mantissa > 2047)
      fail(who, "subband " + std::to_string(i) + " mantissa " + std::to_string(s.mantissa) + " exceeds 2047");
    if (q.style == QuantizationStyle::None && s.mantissa != 0)
      fail(who, "subband " + std::to_string(i) + " has a mantissa, but style 'none' signals only exponents");
  }
}

void write_qcd(ByteWriter& out, const Quantization& q) {
  validate_quantization(q, "QCD");
  MarkerSegment seg(out, marker::QCD, "QCD");
  write_sqcx_spqcx(out, q);
  seg.end();
}

void validate_qcc(const Qcc& qcc, unsigned num_components) {
  const std::string who = "QCC " + std::to_string(qcc.component);
  validate_quantization(qcc.quant, who.c_str());
  if (num_components < 1 || num_components > 16384)
    fail(who.c_str(), std::to_string(num_components) + " components; Csiz must be 1..16384");
  if (qcc.component >= num_components)
    fail(who.c_str(), "component index out of range for " + std::to_string(num_components) + " components");
}

void write_qcc(ByteWriter& out, const Qcc& qcc, unsigned num_components) {
  validate_qcc(qcc, num_components);
  MarkerSegment seg(out, marker::QCC, "QCC");
  if (num_components < 257)
    out.u8(static_cast<std::uint8_t>(qcc.component));
  else
    out.u16(static_cast<std::uint16_t>(qcc.component));
  write_sqcx_spqcx(out, qcc.quant);
  seg.end();
}

}  // namespace codec::cs
