#include "jp2_reader.h"

#include <cmath>
#include <string>

#include "byte_reader.h"

namespace codec::dec {

namespace {

constexpr std::uint32_t box_type(const char (&s)[5]) {
  return (static_cast<std::uint32_t>(static_cast<unsigned char>(s[0])) << 24) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[2])) << 8) | static_cast<unsigned char>(s[3]);
}

struct Box {
  std::uint32_t type;
  std::span<const std::uint8_t> body;
  std::size_t body_offset;
};

// I.4: LBox (4), TBox (4), XLBox (8) when LBox is 1; LBox 0 runs to the end of the enclosing span.
Box next_box(ByteReader& in) {
  const std::size_t at = in.file_offset();
  const std::uint64_t lbox = in.u32("LBox");
  const std::uint32_t type = in.u32("TBox");
  std::uint64_t header = 8, length = lbox;
  if (lbox == 1) {
    length = in.u64("XLBox");
    header = 16;
  } else if (lbox == 0) {
    length = in.remaining() + header;
  }
  if (length < header) fail_at(at, "JP2 box length " + std::to_string(length) + " is shorter than its header");
  if (length - header > in.remaining()) fail_at(at, "JP2 box runs past the end of the file");
  const std::size_t body_offset = in.file_offset();
  return Box{type, in.take(static_cast<std::size_t>(length - header), "JP2 box"), body_offset};
}

}  // namespace

bool looks_like_jp2(std::span<const std::uint8_t> b) {
  static constexpr std::uint8_t kSignature[12] = {0, 0, 0, 0x0C, 'j', 'P', ' ', ' ', 0x0D, 0x0A, 0x87, 0x0A};
  if (b.size() < 12) return false;
  for (int i = 0; i < 12; ++i)
    if (b[static_cast<std::size_t>(i)] != kSignature[i]) return false;
  return true;
}

namespace {

// pclr (I.5.3.4): NE (2), NPC (1), B_i (1 each), then NE rows of NPC values of ceil(B_i / 8) bytes.
Jp2Palette read_pclr(ByteReader in) {
  Jp2Palette p;
  const std::size_t at = in.file_offset();
  p.entries = in.u16("pclr NE");
  const int columns = in.u8("pclr NPC");
  if (p.entries < 1 || p.entries > 1024) fail_at(at, "pclr has " + std::to_string(p.entries) + " entries (1..1024)");
  if (columns < 1) fail_at(at + 2, "pclr has no columns");
  for (int c = 0; c < columns; ++c) {
    const int b = in.u8("pclr B");
    p.precision.push_back((b & 0x7F) + 1);
    p.is_signed.push_back((b & 0x80) != 0);
    if (p.precision.back() > 38)
      fail_at(in.file_offset() - 1, "pclr column of " + std::to_string(p.precision.back()) + " bits");
  }
  p.values.reserve(static_cast<std::size_t>(p.entries) * static_cast<std::size_t>(columns));
  for (int e = 0; e < p.entries; ++e)
    for (int c = 0; c < columns; ++c) {
      const int bits = p.precision[static_cast<std::size_t>(c)];
      std::uint64_t v = 0;
      for (int k = 0; k < (bits + 7) / 8; ++k) v = (v << 8) | in.u8("pclr entry");
      std::int64_t s = static_cast<std::int64_t>(v & ((std::uint64_t{1} << bits) - 1));
      if (p.is_signed[static_cast<std::size_t>(c)] && (s >> (bits - 1))) s -= std::int64_t{1} << bits;
      p.values.push_back(s);
    }
  return p;
}

// cmap (I.5.3.5): per channel CMP (2), MTYP (1: 0 direct, 1 palette), PCOL (1).
std::vector<Jp2ChannelSource> read_cmap(ByteReader in) {
  if (in.remaining() == 0 || in.remaining() % 4 != 0) in.fail("cmap length is not a multiple of 4");
  std::vector<Jp2ChannelSource> out;
  while (!in.at_end()) {
    const std::size_t at = in.file_offset();
    Jp2ChannelSource s;
    s.component = in.u16("cmap CMP");
    const int type = in.u8("cmap MTYP");
    const int column = in.u8("cmap PCOL");
    if (type > 1) fail_at(at + 2, "cmap mapping type " + std::to_string(type) + " is not 0 or 1");
    s.palette_column = type == 1 ? column : -1;
    out.push_back(s);
  }
  return out;
}

// cdef (I.5.3.6): N (2), then N of Cn, Typ, Asoc (2 bytes each).
std::vector<Jp2ChannelDefinition> read_cdef(ByteReader in) {
  const int n = in.u16("cdef N");
  if (in.remaining() != 6u * static_cast<std::size_t>(n))
    in.fail("cdef length disagrees with its N " + std::to_string(n));
  std::vector<Jp2ChannelDefinition> out;
  for (int i = 0; i < n; ++i) {
    Jp2ChannelDefinition d;
    d.channel = in.u16("cdef Cn");
    d.type = in.u16("cdef Typ");
    d.association = in.u16("cdef Asoc");
    out.push_back(d);
  }
  return out;
}

// I.5.3.3 METH 2: an ICC profile (ICC.1) fills the rest of the box. Its header (128 bytes) opens
// with the profile's size, which must fit the box; bytes past it (padding) are not the profile's.
std::vector<std::uint8_t> read_icc_profile(ByteReader& in) {
  constexpr std::size_t kHeaderBytes = 128;
  const std::size_t available = in.remaining();
  if (available < kHeaderBytes)
    in.fail("colr holds " + std::to_string(available) + " bytes of ICC profile, less than a profile header (128)");
  const std::uint32_t size = ByteReader(in).u32("ICC profile size");  // read again as part of the profile
  if (size < kHeaderBytes || size > available)
    in.fail("the ICC profile says it is " + std::to_string(size) + " bytes long, and colr holds " +
            std::to_string(available));
  const std::span<const std::uint8_t> profile = in.take(size, "ICC profile");
  return {profile.begin(), profile.end()};
}

// A capture or display resolution box (I.5.3.7.1, I.5.3.7.2): VR N, D, HR N, D (16 bits each),
// then VR E and HR E (signed bytes); resolution = N / D * 10^E grid points per metre.
GridResolution read_resolution(ByteReader in, const char* box) {
  if (in.remaining() != 10) in.fail(std::string(box) + " holds " + std::to_string(in.remaining()) + " bytes, not 10");
  const double vn = in.u16("VR numerator"), vd = in.u16("VR denominator");
  const double hn = in.u16("HR numerator"), hd = in.u16("HR denominator");
  const auto ve = static_cast<std::int8_t>(in.u8("VR exponent"));
  const auto he = static_cast<std::int8_t>(in.u8("HR exponent"));
  if (vd == 0 || hd == 0) in.fail(std::string(box) + " has a zero denominator");
  return GridResolution{vn / vd * std::pow(10.0, ve), hn / hd * std::pow(10.0, he)};
}

// The resolution superbox (I.5.3.7): a capture and/or a display resolution box (a repeated one
// replaces the first).
void read_res(ByteReader inner, Jp2File& f) {
  while (!inner.at_end()) {
    const Box sub = next_box(inner);
    ByteReader body(sub.body, sub.body_offset);
    if (sub.type == box_type("resc"))
      f.capture_resolution = read_resolution(body, "resc");
    else if (sub.type == box_type("resd"))
      f.display_resolution = read_resolution(body, "resd");
  }
}

void read_jp2_header(ByteReader inner, Jp2File& f) {
  bool have_colr = false;
  while (!inner.at_end()) {
    const Box sub = next_box(inner);
    ByteReader body(sub.body, sub.body_offset);
    if (sub.type == box_type("ihdr")) {
      body.u32("ihdr HEIGHT");
      body.u32("ihdr WIDTH");
      f.ihdr_components = body.u16("ihdr NC");
    } else if (sub.type == box_type("colr") && !have_colr) {
      // I.5.3.3: only the first colr box is read by a conforming JP2 reader.
      have_colr = true;
      const int method = body.u8("METH");
      body.u8("PREC");
      body.u8("APPROX");
      if (method == 1)
        f.colour_space = static_cast<int>(body.u32("EnumCS"));
      else if (method == 2)
        f.icc_profile = read_icc_profile(body);
    } else if (sub.type == box_type("pclr")) {
      f.palette = read_pclr(body);
    } else if (sub.type == box_type("cmap")) {
      f.channel_sources = read_cmap(body);
    } else if (sub.type == box_type("cdef")) {
      f.channel_definitions = read_cdef(body);
    } else if (sub.type == box_type("res ")) {
      read_res(body, f);
    }
  }
  if (f.palette.entries > 0 && f.channel_sources.empty())
    fail_at(inner.file_offset(), "JP2 header has a palette (pclr) but no component mapping (cmap)");
  for (const Jp2ChannelSource& s : f.channel_sources)
    if (s.palette_column >= 0 && s.palette_column >= f.palette.columns())
      fail_at(inner.file_offset(), "cmap names palette column " + std::to_string(s.palette_column) + " of " +
                                       std::to_string(f.palette.columns()));
}

}  // namespace

Jp2File read_jp2(std::span<const std::uint8_t> bytes) {
  Jp2File f;
  ByteReader in(bytes);
  bool have_codestream = false;
  while (!in.at_end() && !have_codestream) {
    const Box box = next_box(in);
    if (box.type == box_type("jp2h")) {
      read_jp2_header(ByteReader(box.body, box.body_offset), f);
    } else if (box.type == box_type("jp2c")) {
      f.codestream = box.body;
      f.codestream_offset = box.body_offset;
      have_codestream = true;
    }
  }
  if (!have_codestream) fail_at(bytes.size(), "the JP2 file has no contiguous codestream box (jp2c)");
  return f;
}

}  // namespace codec::dec
