#include "codec/codestream/jp2.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "codec/codestream/byte_writer.h"
#include "codec/codestream/error.h"

namespace codec::cs {
namespace {

// Box types are four ASCII characters read as a big-endian u32 (T.800 I.4).
constexpr std::uint32_t fourcc(const char (&s)[5]) {
  return (std::uint32_t{static_cast<unsigned char>(s[0])} << 24) |
         (std::uint32_t{static_cast<unsigned char>(s[1])} << 16) |
         (std::uint32_t{static_cast<unsigned char>(s[2])} << 8) | std::uint32_t{static_cast<unsigned char>(s[3])};
}

constexpr std::uint32_t kSignatureContent = 0x0D0A870A;  // CR LF 0x87 LF (I.5.1): catches text-mode mangling
constexpr std::uint32_t kEnumSrgb = 16;                  // EnumCS values, Table I.10
constexpr std::uint32_t kEnumGreyscale = 17;
constexpr std::uint8_t kCompressionWavelet = 7;  // ihdr C: the only value Part 1 defines
constexpr std::uint8_t kBpcVaries = 255;         // ihdr BPC when components differ; bpcc follows

// A box is LBox (u32, whole box length) + TBox + content (I.4). Begin writes a placeholder for
// LBox; end patches it.
std::size_t begin_box(ByteWriter& out, std::uint32_t type) {
  const std::size_t start = out.size();
  out.u32(0);
  out.u32(type);
  return start;
}

void end_box(ByteWriter& out, std::size_t start) {
  const std::size_t length = out.size() - start;
  if (length > 0xFFFFFFFFu) throw CodestreamError("JP2: header box over 4 GiB");
  out.patch_u32(start, static_cast<std::uint32_t>(length));
}

// BPC / bpcc byte (Tables I.3, I.5): depth - 1, bit 7 set for signed.
std::uint8_t depth_byte(const Jp2Component& c) {
  return static_cast<std::uint8_t>((c.is_signed ? 0x80u : 0u) | (c.precision - 1));
}

void validate(const Jp2Header& h) {
  if (h.width == 0 || h.height == 0)
    throw CodestreamError("JP2: image is " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                          "; both sides must be at least 1");
  const std::size_t n = h.components.size();
  if (n < 1 || n > 4)
    throw CodestreamError("JP2: " + std::to_string(n) +
                          " components; the enumerated colour spaces describe 1 to 4 (grey, grey+alpha, sRGB, sRGBA)");
  for (std::size_t i = 0; i < n; ++i)
    if (h.components[i].precision < 1 || h.components[i].precision > 38)
      throw CodestreamError("JP2: component " + std::to_string(i) + " precision " +
                            std::to_string(h.components[i].precision) + " is outside 1..38");
}

void write_ihdr(ByteWriter& out, const Jp2Header& h, bool depths_differ) {
  const std::size_t box = begin_box(out, fourcc("ihdr"));
  out.u32(h.height);  // HEIGHT comes before WIDTH (Table I.2)
  out.u32(h.width);
  out.u16(static_cast<std::uint16_t>(h.components.size()));
  out.u8(depths_differ ? kBpcVaries : depth_byte(h.components[0]));
  out.u8(kCompressionWavelet);
  out.u8(0);  // UnkC: the colour space is known (the colr box says it)
  out.u8(0);  // IPR: no intellectual property box
  end_box(out, box);
}

void write_bpcc(ByteWriter& out, const Jp2Header& h) {
  const std::size_t box = begin_box(out, fourcc("bpcc"));
  for (const Jp2Component& c : h.components) out.u8(depth_byte(c));
  end_box(out, box);
}

void write_colr(ByteWriter& out, const Jp2Header& h) {
  const std::size_t box = begin_box(out, fourcc("colr"));
  out.u8(1);  // METH: enumerated colour space
  out.u8(0);  // PREC: reserved, 0 (Table I.9)
  out.u8(0);  // APPROX: 0 in JP2 files
  out.u32(h.components.size() >= 3 ? kEnumSrgb : kEnumGreyscale);
  end_box(out, box);
}

// Without a cdef box a reader takes every channel past the colour channels as unspecified, so
// opacity has to be declared (I.5.3.6). All channels are listed: colour channel i is type 0
// (colour) associated with colour i + 1; the last is type 1 (opacity) associated with the whole
// image (0).
void write_cdef(ByteWriter& out, const Jp2Header& h) {
  const auto n = static_cast<std::uint16_t>(h.components.size());
  const std::size_t box = begin_box(out, fourcc("cdef"));
  out.u16(n);
  for (std::uint16_t i = 0; i < n; ++i) {
    const bool opacity = i + 1 == n;
    out.u16(i);                                                // Cn
    out.u16(opacity ? 1 : 0);                                  // Typ
    out.u16(static_cast<std::uint16_t>(opacity ? 0 : i + 1));  // Asoc
  }
  end_box(out, box);
}

// A number as a message shows it: 6 significant digits ("1e+200", not 201 of them).
std::string shortest(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// The resolution superbox (I.5.3.7): capture then display, each VR N, D, HR N, D, VR E, HR E.
void write_res(ByteWriter& out, const Jp2Header& h) {
  const std::size_t res = begin_box(out, fourcc("res "));
  const auto write_one = [&](const char(&type)[5], const Jp2Resolution& r) {
    const Jp2ResolutionFraction v = resolution_fraction(r.vertical), hz = resolution_fraction(r.horizontal);
    const std::size_t box = begin_box(out, fourcc(type));
    out.u16(v.numerator);
    out.u16(v.denominator);
    out.u16(hz.numerator);
    out.u16(hz.denominator);
    out.u8(static_cast<std::uint8_t>(v.exponent));
    out.u8(static_cast<std::uint8_t>(hz.exponent));
    end_box(out, box);
  };
  if (h.capture.given()) write_one("resc", h.capture);
  if (h.display.given()) write_one("resd", h.display);
  end_box(out, res);
}

}  // namespace

Jp2ResolutionFraction resolution_fraction(double points_per_metre) {
  if (!(points_per_metre > 0) || !std::isfinite(points_per_metre))
    throw CodestreamError("JP2: a resolution must be a positive number of grid points per metre, not " +
                          shortest(points_per_metre));
  constexpr double kMax = 65535 * (1 + 1e-12);  // with room for the divisions' rounding
  // The smallest exponent from 0 up that leaves the value at most 65535, then the denominator
  // carries its fraction; a negative exponent only below one point per metre. (Negative exponents
  // are the standard's, signed bytes, but grk_decompress 10 misreads them: an exponent of -1 gave
  // its TIFF a zero denominator.)
  int exponent = 0;
  while (points_per_metre / std::pow(10.0, exponent) > kMax) ++exponent;
  while (exponent > -128 && points_per_metre / std::pow(10.0, exponent) < 1) --exponent;
  if (exponent > 127)
    throw CodestreamError("JP2: a resolution of " + shortest(points_per_metre) +
                          " points per metre is more than the box holds (65535e127)");
  const double value = points_per_metre / std::pow(10.0, exponent);
  // Convergents p/q of the continued fraction of `value` while both fit in 16 bits: each is the
  // best approximation with a denominator that small.
  std::int64_t p0 = 1, q0 = 0, p1 = static_cast<std::int64_t>(std::floor(value)), q1 = 1;
  double rest = value - std::floor(value);
  while (rest > 1e-12) {
    const double inverse = 1 / rest;
    const auto a = static_cast<std::int64_t>(std::floor(inverse));
    const std::int64_t p2 = a * p1 + p0, q2 = a * q1 + q0;
    if (p2 > 65535 || q2 > 65535) break;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
    rest = inverse - static_cast<double>(a);
  }
  p1 = std::min<std::int64_t>(p1, 65535);  // the value may exceed 65535 by that rounding
  if (p1 == 0) p1 = 1;                     // below 1e-128 points per metre: the smallest the box holds
  return Jp2ResolutionFraction{static_cast<std::uint16_t>(p1), static_cast<std::uint16_t>(q1),
                               static_cast<std::int8_t>(exponent)};
}

Jp2Header jp2_header_for(const Siz& siz) {
  validate_siz(siz);
  Jp2Header h;
  h.width = static_cast<std::uint32_t>(siz.xsiz - siz.xosiz);
  h.height = static_cast<std::uint32_t>(siz.ysiz - siz.yosiz);
  for (const SizComponent& c : siz.components) h.components.push_back({c.precision, c.is_signed});
  return h;
}

namespace {

// The JP2 family's box layout, shared by JP2 (brand 'jp2 ', T.800 I.5.2) and JPH (brand 'jph ',
// T.814 Annex D): only the file type box's brand and compatibility list differ.
std::vector<std::uint8_t> wrap(const std::vector<std::uint8_t>& codestream, const Jp2Header& h, std::uint32_t brand) {
  validate(h);
  std::vector<std::uint8_t> file;
  ByteWriter out(file);

  const std::size_t signature = begin_box(out, fourcc("jP  "));
  out.u32(kSignatureContent);
  end_box(out, signature);

  const std::size_t ftyp = begin_box(out, fourcc("ftyp"));
  out.u32(brand);  // BR
  out.u32(0);      // MinV
  out.u32(brand);  // CL: the one compatibility entry a reader of the brand looks for
  end_box(out, ftyp);

  bool depths_differ = false;
  for (const Jp2Component& c : h.components)
    depths_differ |= c.precision != h.components[0].precision || c.is_signed != h.components[0].is_signed;
  const bool has_opacity = h.components.size() == 2 || h.components.size() == 4;

  const std::size_t jp2h = begin_box(out, fourcc("jp2h"));
  write_ihdr(out, h, depths_differ);  // ihdr must be the first box in jp2h (I.5.3)
  if (depths_differ) write_bpcc(out, h);
  write_colr(out, h);
  if (has_opacity) write_cdef(out, h);
  if (h.capture.given() || h.display.given()) write_res(out, h);
  end_box(out, jp2h);

  // The codestream box may exceed 4 GiB: then LBox = 1 and the length goes in XLBox (I.4).
  const std::uint64_t plain_length = 8 + static_cast<std::uint64_t>(codestream.size());
  if (plain_length <= 0xFFFFFFFFu) {
    out.u32(static_cast<std::uint32_t>(plain_length));
    out.u32(fourcc("jp2c"));
  } else {
    out.u32(1);
    out.u32(fourcc("jp2c"));
    out.u64(plain_length + 8);
  }
  out.bytes(codestream);
  return file;
}

}  // namespace

std::vector<std::uint8_t> wrap_jp2(const std::vector<std::uint8_t>& codestream, const Jp2Header& h) {
  return wrap(codestream, h, fourcc("jp2 "));
}

std::vector<std::uint8_t> wrap_jph(const std::vector<std::uint8_t>& codestream, const Jp2Header& h) {
  return wrap(codestream, h, fourcc("jph "));
}

}  // namespace codec::cs
