#include "codec/codestream/main_header.h"

#include <string>

#include "codec/codestream/delimiters.h"
#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"

namespace codec::cs {
namespace {

// Components named twice would leave it to the decoder which one wins; reject instead.
template <class Segment>
void check_unique_components(const std::vector<Segment>& segments, std::size_t num_components, const char* name) {
  std::vector<bool> seen(num_components, false);
  for (const Segment& s : segments) {
    if (s.component >= num_components) continue;  // reported by the segment's own validation
    if (seen[s.component])
      throw CodestreamError(std::string(name) + ": component " + std::to_string(s.component) + " appears twice");
    seen[s.component] = true;
  }
}

void check_mct(const MainHeader& h) {
  const auto& comps = h.siz.components;
  if (comps.size() < 3)
    throw CodestreamError("COD: the multiple component transform needs at least 3 components, have " +
                          std::to_string(comps.size()));
  for (unsigned c = 1; c < 3; ++c) {
    if (comps[c].xrsiz != comps[0].xrsiz || comps[c].yrsiz != comps[0].yrsiz)
      throw CodestreamError(
          "COD: the multiple component transform needs components 0-2 equally subsampled; component " +
          std::to_string(c) + " differs");
    if (coding_style_for(h, c).transform != coding_style_for(h, 0).transform)
      throw CodestreamError(
          "COD: the multiple component transform needs one wavelet filter in components 0-2; component " +
          std::to_string(c) + " differs");
    // Not a T.800 rule: OpenJPEG 2.5 refuses to decode (tile "dimension" mismatch before its
    // inverse MCT) when components 0-2 have different level counts, so we never write that.
    if (coding_style_for(h, c).levels != coding_style_for(h, 0).levels)
      throw CodestreamError(
          "COD: with the multiple component transform, components 0-2 must share one level count "
          "(OpenJPEG cannot decode otherwise); component " +
          std::to_string(c) + " differs");
  }
}

void write_cap(ByteWriter& out, std::uint16_t ccap15) {
  MarkerSegment seg(out, marker::CAP, "CAP");
  out.u32(std::uint32_t{1} << (32 - 15));  // Pcap: bit for Part 15, counted from the MSB as Part 1
  out.u16(ccap15);
  seg.end();
}

}  // namespace

std::uint16_t ht_only_ccap15(bool irreversible, int largest_magnitude_bitplanes) {
  const int b = largest_magnitude_bitplanes;
  // MAGB (T.814 Table A.5): B up to 8 -> 0; 9..27 -> B - 8; 28..47 -> 13 + B / 4; above -> 31.
  const int magb = b <= 8 ? 0 : b < 28 ? b - 8 : b < 48 ? 13 + (b >> 2) : 31;
  return static_cast<std::uint16_t>((irreversible ? 0x0020 : 0) | magb);
}

const CodingStyle& coding_style_for(const MainHeader& h, unsigned component) {
  for (const Coc& c : h.cocs)
    if (c.component == component) return c.style;
  return h.cod.style;
}

const Quantization& quantization_for(const MainHeader& h, unsigned component) {
  for (const Qcc& q : h.qccs)
    if (q.component == component) return q.quant;
  return h.qcd;
}

void validate_main_header(const MainHeader& h) {
  validate_siz(h.siz);
  const auto n = static_cast<unsigned>(h.siz.components.size());
  validate_cod(h.cod);
  for (const Coc& c : h.cocs) validate_coc(c, n);
  check_unique_components(h.cocs, n, "COC");
  validate_quantization(h.qcd, "QCD");
  for (const Qcc& q : h.qccs) validate_qcc(q, n);
  check_unique_components(h.qccs, n, "QCC");
  if (h.cod.mct) check_mct(h);
  if (h.ccap15 && !(h.siz.rsiz & kRsizCapabilitiesInCap))
    throw CodestreamError("SIZ: a CAP marker segment needs Rsiz bit 14 set");

  // The decoder reads one step per subband of the component, so the counts must agree.
  for (unsigned c = 0; c < n; ++c) {
    const Quantization& q = quantization_for(h, c);
    if (q.style == QuantizationStyle::ScalarDerived) continue;
    const unsigned levels = coding_style_for(h, c).levels;
    if (q.steps.size() != subband_count(levels))
      throw CodestreamError("QCD/QCC: component " + std::to_string(c) + " has " + std::to_string(levels) +
                            " decomposition levels, so needs " + std::to_string(subband_count(levels)) +
                            " step sizes, not " + std::to_string(q.steps.size()));
  }
}

void write_main_header(ByteWriter& out, const MainHeader& h) {
  validate_main_header(h);
  const std::size_t start = out.size();
  try {
    const auto n = static_cast<unsigned>(h.siz.components.size());
    write_soc(out);
    write_siz(out, h.siz);  // SIZ must follow SOC directly (T.800 A.3)
    if (h.ccap15) write_cap(out, *h.ccap15);
    write_cod(out, h.cod);
    for (const Coc& c : h.cocs) write_coc(out, c, n);
    write_qcd(out, h.qcd);
    for (const Qcc& q : h.qccs) write_qcc(out, q, n);
    for (const Comment& c : h.comments) write_com(out, c);
  } catch (...) {
    out.truncate(start);
    throw;
  }
}

}  // namespace codec::cs
