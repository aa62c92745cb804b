#include "codec/codestream/cod.h"

#include <string>

#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"
#include "fail.h"

namespace codec::cs {
namespace {

// Scod / Scoc bits (T.800 Tables A.13 and A.23).
constexpr std::uint8_t kUserPrecincts = 0x01;
constexpr std::uint8_t kSop = 0x02;
constexpr std::uint8_t kEph = 0x04;

// SPcod / SPcoc (Table A.15): levels, xcb - 2, ycb - 2, block style, transform, then one byte per
// resolution with PPy in the high nibble and PPx in the low one (Table A.21).
void write_spcox(ByteWriter& out, const CodingStyle& s) {
  out.u8(static_cast<std::uint8_t>(s.levels));
  out.u8(static_cast<std::uint8_t>(s.xcb - 2));
  out.u8(static_cast<std::uint8_t>(s.ycb - 2));
  out.u8(s.block_style);
  out.u8(static_cast<std::uint8_t>(s.transform));
  for (const PrecinctSize& p : s.precincts) out.u8(static_cast<std::uint8_t>((p.ppy << 4) | p.ppx));
}

}  // namespace

void validate_coding_style(const CodingStyle& s, const char* who) {
  if (s.levels > 32) fail(who, std::to_string(s.levels) + " decomposition levels; at most 32 are allowed");
  if (s.xcb < 2 || s.xcb > 10 || s.ycb < 2 || s.ycb > 10)
    fail(who, "code-block exponents " + std::to_string(s.xcb) + "x" + std::to_string(s.ycb) + " must each be 2..10");
  if (s.xcb + s.ycb > 12)
    fail(who, "code-block exponents " + std::to_string(s.xcb) + "+" + std::to_string(s.ycb) +
                  " exceed 12 (at most 4096 samples per block)");
  if (s.transform != WaveletTransform::Irreversible9x7 && s.transform != WaveletTransform::Reversible5x3)
    fail(who, "wavelet transform " + std::to_string(static_cast<unsigned>(s.transform)) + " is not 0 (9/7) or 1 (5/3)");
  if (s.precincts.empty()) return;
  if (s.precincts.size() != s.levels + 1)
    fail(who, std::to_string(s.precincts.size()) + " precinct sizes given for " + std::to_string(s.levels + 1) +
                  " resolutions");
  for (std::size_t r = 0; r < s.precincts.size(); ++r) {
    const PrecinctSize& p = s.precincts[r];
    if (p.ppx > 15 || p.ppy > 15)
      fail(who, "precinct exponents " + std::to_string(p.ppx) + "," + std::to_string(p.ppy) + " at resolution " +
                    std::to_string(r) + " exceed 15");
    if (r > 0 && (p.ppx == 0 || p.ppy == 0))
      fail(who, "precinct exponent 0 at resolution " + std::to_string(r) + "; only resolution 0 may use it");
  }
}

void validate_cod(const Cod& cod) {
  validate_coding_style(cod.style, "COD");
  if (cod.order > ProgressionOrder::CPRL)
    fail("COD", "progression order " + std::to_string(static_cast<unsigned>(cod.order)) + " is not 0..4");
  if (cod.layers < 1 || cod.layers > 65535)
    fail("COD", std::to_string(cod.layers) + " quality layers; must be 1..65535");
}

void validate_coc(const Coc& coc, unsigned num_components) {
  const std::string who = "COC " + std::to_string(coc.component);
  validate_coding_style(coc.style, who.c_str());
  if (num_components < 1 || num_components > 16384)
    fail(who.c_str(), std::to_string(num_components) + " components; Csiz must be 1..16384");
  if (coc.component >= num_components)
    fail(who.c_str(), "component index out of range for " + std::to_string(num_components) + " components");
}

void write_cod(ByteWriter& out, const Cod& cod) {
  validate_cod(cod);

  MarkerSegment seg(out, marker::COD, "COD");
  out.u8(static_cast<std::uint8_t>((cod.style.precincts.empty() ? 0 : kUserPrecincts) | (cod.sop ? kSop : 0) |
                                   (cod.eph ? kEph : 0)));
  // SGcod (Table A.14): progression order, layers, multiple component transform.
  out.u8(static_cast<std::uint8_t>(cod.order));
  out.u16(static_cast<std::uint16_t>(cod.layers));
  out.u8(cod.mct ? 1 : 0);
  write_spcox(out, cod.style);
  seg.end();
}

void write_coc(ByteWriter& out, const Coc& coc, unsigned num_components) {
  validate_coc(coc, num_components);
  MarkerSegment seg(out, marker::COC, "COC");
  if (num_components < 257)
    out.u8(static_cast<std::uint8_t>(coc.component));
  else
    out.u16(static_cast<std::uint16_t>(coc.component));
  // Scoc only has the user-precinct bit; SOP and EPH are tile-wide and live in Scod.
  out.u8(coc.style.precincts.empty() ? 0 : kUserPrecincts);
  write_spcox(out, coc.style);
  seg.end();
}

}  // namespace codec::cs
