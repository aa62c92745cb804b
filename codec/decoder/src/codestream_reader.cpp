#include "codestream_reader.h"

#include <algorithm>
#include <string>

#include "byte_reader.h"
#include "codec/codestream/markers.h"
#include "codec/structure/error.h"

namespace codec::dec {

namespace mk = cs::marker;

namespace {

std::string hex(std::uint32_t code, int digits_wanted = 4) {
  static const char* digits = "0123456789ABCDEF";
  std::string s = "0x";
  for (int shift = 4 * (digits_wanted - 1); shift >= 0; shift -= 4) s += digits[(code >> shift) & 0xF];
  return s;
}

// A marker segment's body: Lxxx counts itself but not the marker (A.1.4).
ByteReader segment_body(ByteReader& in, std::size_t base, const char* name) {
  const std::size_t at = in.file_offset();
  const std::uint16_t length = in.u16(name);
  if (length < 2) fail_at(at, std::string(name) + " length " + std::to_string(length) + " is below 2");
  const std::size_t body_at = in.position();
  return ByteReader(in.take(length - 2u, name), base + body_at);
}

// Components are named by one byte, or two when Csiz >= 257 (A.6.2).
int component_index(ByteReader& in, const Siz& siz, const char* name) {
  const std::size_t at = in.file_offset();
  const int c = siz.components.size() >= 257 ? in.u16(name) : in.u8(name);
  if (c >= static_cast<int>(siz.components.size()))
    fail_at(at, std::string(name) + " names component " + std::to_string(c) + " of " +
                    std::to_string(siz.components.size()));
  return c;
}

Siz read_siz(ByteReader body) {
  Siz s;
  s.rsiz = body.u16("Rsiz");
  const std::int64_t xsiz = body.u32("Xsiz"), ysiz = body.u32("Ysiz");
  const std::int64_t xo = body.u32("XOsiz"), yo = body.u32("YOsiz");
  const std::int64_t xt = body.u32("XTsiz"), yt = body.u32("YTsiz");
  const std::int64_t xto = body.u32("XTOsiz"), yto = body.u32("YTOsiz");
  const std::size_t csiz_at = body.file_offset();
  const int csiz = body.u16("Csiz");
  if (csiz < 1 || csiz > 16384) fail_at(csiz_at, "SIZ Csiz " + std::to_string(csiz) + " is outside 1..16384");
  if (body.remaining() != 3u * static_cast<std::size_t>(csiz))
    fail_at(csiz_at, "SIZ length disagrees with Csiz " + std::to_string(csiz) + " (Lsiz = 38 + 3 Csiz)");
  s.grid.image = Rect{xo, yo, xsiz, ysiz};
  s.grid.tile_width = xt;
  s.grid.tile_height = yt;
  s.grid.tile_x0 = xto;
  s.grid.tile_y0 = yto;
  try {
    validate(s.grid);
  } catch (const EncodeError& e) {
    fail_at(csiz_at - 36, std::string("SIZ: ") + e.what());
  }
  for (int c = 0; c < csiz; ++c) {
    const std::size_t at = body.file_offset();
    ComponentSize comp;
    const int ssiz = body.u8("Ssiz");
    comp.is_signed = (ssiz & 0x80) != 0;
    comp.precision = (ssiz & 0x7F) + 1;
    if (comp.precision > 38)
      fail_at(at,
              "SIZ component " + std::to_string(c) + " has " + std::to_string(comp.precision) + " bits (at most 38)");
    comp.dx = body.u8("XRsiz");
    comp.dy = body.u8("YRsiz");
    if (comp.dx < 1 || comp.dy < 1)
      fail_at(at + 1, "SIZ component " + std::to_string(c) + " has a sampling factor of 0");
    s.components.push_back(comp);
  }
  return s;
}

// SPcod / SPcoc (Table A.15); `precincts_defined` is Scod/Scoc bit 0.
ComponentCoding read_component_coding(ByteReader& body, bool precincts_defined, const char* name) {
  ComponentCoding c;
  std::size_t at = body.file_offset();
  c.levels = body.u8("number of decomposition levels");
  if (c.levels > 32)
    fail_at(at, std::string(name) + ": " + std::to_string(c.levels) + " decomposition levels (at most 32)");
  at = body.file_offset();
  c.xcb = body.u8("code-block width") + 2;
  c.ycb = body.u8("code-block height") + 2;
  if (c.xcb > 10 || c.ycb > 10 || c.xcb + c.ycb > 12)
    fail_at(at, std::string(name) + ": code-block size 2^" + std::to_string(c.xcb) + " x 2^" + std::to_string(c.ycb) +
                    " is not allowed (exponents 2..10, sum at most 12)");
  at = body.file_offset();
  c.block_style = body.u8("code-block style");
  // Bit 0x40: HT code-blocks (T.814 A.2, Table A.4); with 0x80 also set, the mixed mode where each
  // code-block may be either, which this decoder does not read.
  if (c.block_style & 0x80)
    fail_at(at, std::string(name) + (c.block_style & 0x40
                                         ? ": mixed HT / Part 1 code-blocks (T.814 style bits 0xC0) are not supported"
                                         : ": code-block style bit 7 is reserved"));
  at = body.file_offset();
  const int transform = body.u8("wavelet transform");
  if (transform > 1)
    fail_at(at, std::string(name) + ": wavelet transform " + std::to_string(transform) +
                    " is not Part 1's 9/7 (0) or 5/3 (1)");
  c.reversible = transform == 1;
  if (precincts_defined) {
    for (int r = 0; r <= c.levels; ++r) {
      at = body.file_offset();
      const int b = body.u8("precinct size");
      const int ppx = b & 0xF, ppy = b >> 4;
      if (r > 0 && (ppx == 0 || ppy == 0))
        fail_at(at, std::string(name) + ": precinct exponent 0 above resolution 0 (A.6.1)");
      c.precincts.emplace_back(ppx, ppy);
    }
  }
  return c;
}

Cod read_cod(ByteReader body) {
  Cod cod;
  std::size_t at = body.file_offset();
  const int scod = body.u8("Scod");
  if (scod & ~0x07) fail_at(at, "COD Scod " + std::to_string(scod) + " has reserved bits set");
  cod.sop = (scod & 2) != 0;
  cod.eph = (scod & 4) != 0;
  at = body.file_offset();
  const int order = body.u8("progression order");
  if (order > 4) fail_at(at, "COD progression order " + std::to_string(order) + " is not one of 0..4");
  cod.order = static_cast<t2::Order>(order);
  at = body.file_offset();
  cod.layers = body.u16("number of layers");
  if (cod.layers < 1) fail_at(at, "COD has 0 layers");
  at = body.file_offset();
  cod.mct = body.u8("multiple component transform");
  if (cod.mct > 1) fail_at(at, "COD multiple component transform " + std::to_string(cod.mct) + " is not 0 or 1");
  cod.component = read_component_coding(body, (scod & 1) != 0, "COD");
  return cod;
}

Quantization read_quantization(ByteReader& body, const char* name) {
  Quantization q;
  const std::size_t at = body.file_offset();
  const int s = body.u8("Sqcd");
  q.style = s & 0x1F;
  q.guard_bits = s >> 5;
  if (q.style > 2) fail_at(at, std::string(name) + ": quantisation style " + std::to_string(q.style) + " is not 0..2");
  if (q.style == 0) {
    while (!body.at_end()) q.steps.push_back(StepSize{body.u8("exponent") >> 3, 0});
  } else {
    while (body.remaining() >= 2) {
      const int v = body.u16("step size");
      q.steps.push_back(StepSize{v >> 11, v & 0x7FF});
    }
    if (!body.at_end()) body.fail(std::string(name) + ": odd number of step-size bytes");
  }
  if (q.steps.empty()) fail_at(at, std::string(name) + " carries no step sizes");
  if (q.style == 1 && q.steps.size() != 1) q.steps.resize(1);
  return q;
}

void read_rgn(ByteReader body, const Siz& siz, HeaderMarkers& h) {
  const int c = component_index(body, siz, "RGN component");
  const std::size_t at = body.file_offset();
  const int style = body.u8("Srgn");
  if (style != 0) fail_at(at, "RGN style " + std::to_string(style) + " is not the maximum shift method (0)");
  h.roi_shift[c] = body.u8("SPrgn");
}

// CAP (T.800 A.5.2 as amended by T.814 A.3): Pcap names the parts whose capabilities follow, one
// 16-bit Ccap per bit set. Only Part 15's (bit 15 from the most significant: HTJ2K) is decoded here;
// what it says (HT sets, refinement passes, magnitude bound) needs no preparation, so it is checked
// for its length only. Any other part is refused.
void read_cap(ByteReader body) {
  const std::size_t at = body.file_offset();
  const std::uint32_t pcap = body.u32("Pcap");
  constexpr std::uint32_t kPart15 = std::uint32_t{1} << (32 - 15);
  if (pcap & ~kPart15)
    fail_at(at, "CAP: capabilities of parts other than Part 15 (Pcap " + hex(pcap, 8) + ") are not supported");
  if (pcap & kPart15) body.u16("Ccap15");
  if (!body.at_end())
    body.fail("CAP: " + std::to_string(body.remaining()) + " byte(s) beyond the Ccap fields Pcap announces");
}

// POC (A.6.6, Table A.32): RSpoc, CSpoc, LYEpoc, REpoc, CEpoc, Ppoc per progression, component
// fields two bytes wide when Csiz >= 257. Each range is checked so that the packet walk can trust it.
void read_poc(ByteReader body, const Siz& siz, HeaderMarkers& h) {
  const bool wide = siz.components.size() >= 257;
  const std::size_t entry = wide ? 9 : 7;
  if (body.remaining() == 0 || body.remaining() % entry != 0)
    body.fail("POC length is not 2 + " + std::to_string(entry) + " x the number of progressions");
  const int components = static_cast<int>(siz.components.size());
  while (!body.at_end()) {
    const std::size_t at = body.file_offset();
    ProgressionChange p;
    p.res_start = body.u8("RSpoc");
    p.comp_start = wide ? body.u16("CSpoc") : body.u8("CSpoc");
    p.layer_end = body.u16("LYEpoc");
    p.res_end = body.u8("REpoc");
    p.comp_end = wide ? body.u16("CEpoc") : body.u8("CEpoc");
    // Table A.32: CEpoc 0 stands for 256 (resp. 16384 when two bytes wide).
    if (p.comp_end == 0) p.comp_end = wide ? 16384 : 256;
    p.comp_end = std::min(p.comp_end, components);
    const int order = body.u8("Ppoc");
    if (order > 4) fail_at(at + entry - 1, "POC progression order " + std::to_string(order) + " is not one of 0..4");
    p.order = static_cast<t2::Order>(order);
    if (p.res_start >= p.res_end || p.res_end > 33 || p.comp_start >= p.comp_end || p.layer_end == 0)
      fail_at(at, "POC progression with empty or reversed ranges (RS " + std::to_string(p.res_start) + ".." +
                      std::to_string(p.res_end) + ", CS " + std::to_string(p.comp_start) + ".." +
                      std::to_string(p.comp_end) + ", LYE " + std::to_string(p.layer_end) + ")");
    h.poc.push_back(p);
  }
}

// PPM / PPT (A.7.4, A.7.5): Zppm/Zppt, then packed header bytes appended to `out` (the segments
// are taken in the order they appear).
void read_packed_headers(ByteReader body, const char* name, std::vector<std::uint8_t>& out) {
  body.u8(name);  // Zppm / Zppt
  const auto bytes = body.take(body.remaining(), name);
  out.insert(out.end(), bytes.begin(), bytes.end());
}

// Markers allowed in both main and tile-part headers. Returns false for markers it does not know.
bool read_common_marker(std::uint16_t code, ByteReader& in, std::size_t base, const Siz& siz, HeaderMarkers& h,
                        bool first_tile_part, std::vector<std::string>& warnings) {
  const std::size_t at = in.file_offset() - 2;
  auto coding_marker_in_later_part = [&](const char* name) {
    if (!first_tile_part) fail_at(at, std::string(name) + " in a tile-part other than the first (A.4.2)");
  };
  switch (code) {
    case mk::COD:
      coding_marker_in_later_part("COD");
      h.cod = read_cod(segment_body(in, base, "COD"));
      return true;
    case mk::COC: {
      coding_marker_in_later_part("COC");
      ByteReader body = segment_body(in, base, "COC");
      const int c = component_index(body, siz, "COC component");
      const std::size_t sat = body.file_offset();
      const int scoc = body.u8("Scoc");
      if (scoc & ~1) fail_at(sat, "COC Scoc has reserved bits set");
      h.coc[c] = read_component_coding(body, scoc & 1, "COC");
      return true;
    }
    case mk::QCD: {
      coding_marker_in_later_part("QCD");
      ByteReader body = segment_body(in, base, "QCD");
      h.qcd = read_quantization(body, "QCD");
      return true;
    }
    case mk::QCC: {
      coding_marker_in_later_part("QCC");
      ByteReader body = segment_body(in, base, "QCC");
      const int c = component_index(body, siz, "QCC component");
      h.qcc[c] = read_quantization(body, "QCC");
      return true;
    }
    case mk::RGN:
      coding_marker_in_later_part("RGN");
      read_rgn(segment_body(in, base, "RGN"), siz, h);
      return true;
    case mk::COM:
    case mk::PLT:
    case mk::PLM:
    case mk::TLM:
    case mk::CRG:
      // Informational or redundant: packet and tile-part lengths are found by parsing (the
      // decoder never trusts them), comments and registration do not change the samples.
      segment_body(in, base, "marker segment");
      return true;
    case mk::POC:
      // A.6.6: POC may be in any tile-part header of the tile; the progressions accumulate.
      read_poc(segment_body(in, base, "POC"), siz, h);
      return true;
    case mk::PPM:
      fail_at(at, "PPM in a tile-part header (A.7.4: main header only)");
    case mk::PPT:
      fail_at(at, "PPT in the main header (A.7.5: tile-part headers only)");
    case mk::CAP:
      read_cap(segment_body(in, base, "CAP"));
      return true;
    default:
      break;
  }
  // A.1.3: markers 0xFF30..0xFF3F have no segment; any other unknown marker has a length we can skip.
  if (code >= 0xFF30 && code <= 0xFF3F) return true;
  if (code < 0xFF40) return false;
  warnings.push_back("at byte " + std::to_string(at) + ": unknown marker " + hex(code) + " skipped");
  segment_body(in, base, "unknown marker segment");
  return true;
}

void read_tile_part(ByteReader& in, std::size_t base, Codestream& cs, std::size_t sot_at) {
  ByteReader sot = segment_body(in, base, "SOT");
  if (sot.remaining() != 8) fail_at(sot_at + 2, "SOT length is not 10");
  const std::size_t isot_at = sot.file_offset();
  const int isot = sot.u16("Isot");
  if (isot >= cs.siz.grid.tile_count())
    fail_at(isot_at, "SOT tile index " + std::to_string(isot) + " of a grid of " +
                         std::to_string(cs.siz.grid.tile_count()) + " tiles");
  const std::uint32_t psot = sot.u32("Psot");
  const int tpsot = sot.u8("TPsot");
  sot.u8("TNsot");

  auto it = std::find_if(cs.tiles.begin(), cs.tiles.end(), [&](const TileStream& t) { return t.index == isot; });
  const bool first = it == cs.tiles.end();
  if (first) {
    if (tpsot != 0)
      cs.warnings.push_back("at byte " + std::to_string(sot_at) + ": tile " + std::to_string(isot) +
                            " begins with tile-part " + std::to_string(tpsot));
    cs.tiles.emplace_back();
    cs.tiles.back().index = isot;
    it = cs.tiles.end() - 1;
  } else if (tpsot != static_cast<int>(it->parts.size())) {
    cs.warnings.push_back("at byte " + std::to_string(sot_at) + ": tile-part " + std::to_string(tpsot) + " of tile " +
                          std::to_string(isot) + " out of order");
  }
  TileStream& tile = *it;

  for (;;) {
    const std::size_t at = in.file_offset();
    const std::uint16_t code = in.u16("marker");
    if (code == mk::SOD) break;
    if (code == mk::PPT) {
      if (cs.has_ppm) fail_at(at, "PPT in a stream whose main header has PPM (A.7.4)");
      tile.packed_headers = true;
      read_packed_headers(segment_body(in, base, "PPT"), "PPT", tile.headers);
      continue;
    }
    if (!read_common_marker(code, in, base, cs.siz, tile.header, first, cs.warnings))
      fail_at(at, "expected a marker segment in the tile-part header, found " + hex(code));
  }
  const std::size_t data_at = in.position();
  const std::size_t header_len = data_at - (sot_at - base);
  std::size_t data_len;
  if (psot == 0) {
    // A.4.2: Psot 0 is the last tile-part, running to EOC.
    data_len = in.remaining();
    if (data_len >= 2) {
      // Do not count a final EOC as data.
      ByteReader probe = in;
      probe.skip(data_len - 2, "tile-part data");
      if (probe.peek_u16() == mk::EOC) data_len -= 2;
    }
  } else {
    if (psot < header_len)
      fail_at(sot_at + 6, "SOT Psot " + std::to_string(psot) + " is shorter than the tile-part header");
    data_len = psot - header_len;
    if (data_len > in.remaining()) {
      cs.warnings.push_back("truncated: tile-part of tile " + std::to_string(isot) + " at byte " +
                            std::to_string(sot_at) + " ends " + std::to_string(data_len - in.remaining()) +
                            " byte(s) early");
      data_len = in.remaining();
    }
  }
  if (tile.parts.empty()) tile.first_offset = base + data_at;
  tile.parts.push_back(in.take(data_len, "tile-part data"));
  cs.tile_part_tiles.push_back(isot);
}

// A.7.4: the PPM bytes are, for each tile-part in stream order, Nppm (4 bytes) and that many
// bytes of packet headers. Each tile receives its tile-parts' runs, joined.
void distribute_ppm(Codestream& cs) {
  ByteReader in(cs.ppm);
  for (const int tile_index : cs.tile_part_tiles) {
    auto it =
        std::find_if(cs.tiles.begin(), cs.tiles.end(), [&](const TileStream& t) { return t.index == tile_index; });
    it->packed_headers = true;
    if (in.remaining() < 4) {
      cs.warnings.push_back("PPM: the packed headers end before tile-part of tile " + std::to_string(tile_index));
      continue;
    }
    const std::uint32_t n = in.u32("Nppm");
    if (n > in.remaining()) {
      cs.warnings.push_back("PPM: Nppm " + std::to_string(n) + " for tile " + std::to_string(tile_index) +
                            " runs past the PPM data");
      const auto rest = in.take(in.remaining(), "Ippm");
      it->headers.insert(it->headers.end(), rest.begin(), rest.end());
      continue;
    }
    const auto run = in.take(n, "Ippm");
    it->headers.insert(it->headers.end(), run.begin(), run.end());
  }
}

// Tile-parts, from the first SOT (just read) until EOC or the end of the bytes.
void read_tile_parts(ByteReader& in, std::size_t base, Codestream& cs) {
  std::size_t sot_at = in.file_offset() - 2;
  for (;;) {
    try {
      read_tile_part(in, base, cs, sot_at);
    } catch (const DecodeError& e) {
      // A tile-part header cut off by the end of the stream is a truncation, not a malformed file.
      if (in.remaining() == 0 || std::string(e.what()).find("truncated") != std::string::npos) {
        cs.warnings.push_back(std::string("truncated: ") + e.what());
        return;
      }
      throw;
    }
    if (in.remaining() < 2) {
      cs.warnings.push_back("truncated: the stream ends without EOC");
      return;
    }
    sot_at = in.file_offset();
    const std::uint16_t code = in.u16("marker");
    if (code == mk::EOC) break;
    if (code != mk::SOT) {
      cs.warnings.push_back("at byte " + std::to_string(sot_at) + ": expected SOT or EOC, found " + hex(code) +
                            "; the rest of the stream is ignored");
      break;
    }
  }
}

}  // namespace

Codestream read_codestream(std::span<const std::uint8_t> bytes, std::size_t base) {
  Codestream cs;
  ByteReader in(bytes, base);
  if (in.u16("SOC marker") != mk::SOC) fail_at(base, "not a JPEG 2000 codestream (no SOC marker)");
  if (in.u16("SIZ marker") != mk::SIZ) fail_at(base + 2, "SIZ must follow SOC (A.4.1)");
  cs.siz = read_siz(segment_body(in, base, "SIZ"));

  // Main header, up to the first SOT.
  for (;;) {
    const std::size_t at = in.file_offset();
    if (in.remaining() < 2) {
      cs.warnings.push_back("truncated: the stream ends in the main header");
      return cs;
    }
    const std::uint16_t code = in.u16("marker");
    if (code == mk::SOT) break;
    if (code == mk::EOC) return cs;
    if (code == mk::PPM) {
      cs.has_ppm = true;
      read_packed_headers(segment_body(in, base, "PPM"), "PPM", cs.ppm);
      continue;
    }
    if (!read_common_marker(code, in, base, cs.siz, cs.main, true, cs.warnings))
      fail_at(at, "expected a marker segment in the main header, found " + hex(code));
  }
  if (!cs.main.cod) fail_at(in.file_offset(), "the main header has no COD marker");
  if (!cs.main.qcd) fail_at(in.file_offset(), "the main header has no QCD marker");

  read_tile_parts(in, base, cs);
  if (cs.has_ppm) distribute_ppm(cs);
  return cs;
}

namespace {
template <class T>
const T* find_in(const std::map<int, T>& m, int c) {
  auto it = m.find(c);
  return it == m.end() ? nullptr : &it->second;
}
}  // namespace

TileParams resolve_tile_params(const Codestream& cs, const TileStream& tile) {
  TileParams p;
  const HeaderMarkers& th = tile.header;
  const HeaderMarkers& mh = cs.main;
  p.cod = th.cod ? *th.cod : *mh.cod;
  // The tile's progressions: the main header's POC records, then its tile-parts' records. T.800
  // A.1.4 reads as a tile-part POC replacing the main header's, but grk_compress writes a main
  // POC with the packet order it used plus tile-part POCs that repeat its ranges with order 0,
  // and OpenJPEG and Grok decode by appending tile-part records to the main header's (the tile's
  // records then only reach packets not sent yet). We follow them; the two readings differ only
  // for a tile with POC in both places whose records disagree.
  p.poc = mh.poc;
  p.poc.insert(p.poc.end(), th.poc.begin(), th.poc.end());
  for (int c = 0; c < static_cast<int>(cs.siz.components.size()); ++c) {
    TileComponentParams tc;
    if (const auto* coc = find_in(th.coc, c))
      tc.coding = *coc;
    else if (th.cod)
      tc.coding = th.cod->component;
    else if (const auto* mcoc = find_in(mh.coc, c))
      tc.coding = *mcoc;
    else
      tc.coding = mh.cod->component;

    if (const auto* qcc = find_in(th.qcc, c))
      tc.quantization = *qcc;
    else if (th.qcd)
      tc.quantization = *th.qcd;
    else if (const auto* mqcc = find_in(mh.qcc, c))
      tc.quantization = *mqcc;
    else
      tc.quantization = *mh.qcd;

    if (const auto* r = find_in(th.roi_shift, c))
      tc.roi_shift = *r;
    else if (const auto* mr = find_in(mh.roi_shift, c))
      tc.roi_shift = *mr;

    const std::size_t bands = 3u * static_cast<std::size_t>(tc.coding.levels) + 1;
    if (tc.quantization.style != 1 && tc.quantization.steps.size() < bands)
      throw DecodeError("tile " + std::to_string(tile.index) + " component " + std::to_string(c) +
                        ": the quantisation marker gives " + std::to_string(tc.quantization.steps.size()) +
                        " step sizes for " + std::to_string(bands) + " subbands");
    p.components.push_back(std::move(tc));
  }
  if (p.cod.mct == 1) {
    if (cs.siz.components.size() < 3)
      throw DecodeError("COD asks for a component transform but the image has fewer than 3 components");
    const auto& c0 = cs.siz.components[0];
    for (int c = 1; c < 3; ++c) {
      const auto& ci = cs.siz.components[static_cast<std::size_t>(c)];
      if (ci.dx != c0.dx || ci.dy != c0.dy)
        throw DecodeError("the component transform needs components 0..2 of equal sampling (G.2)");
      if (p.components[static_cast<std::size_t>(c)].coding.reversible != p.components[0].coding.reversible)
        throw DecodeError("the component transform needs components 0..2 to use the same wavelet (G.2)");
    }
  }
  return p;
}

}  // namespace codec::dec
