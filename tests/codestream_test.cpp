// Codestream syntax and JP2 wrapper: byte-exact marker segments derived from T.800 Annex A's tables,
// validation, and codestreams of empty packets decoded by OpenJPEG and Grok.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <sys/wait.h>

#include "codec/codestream/byte_writer.h"
#include "codec/codestream/cod.h"
#include "codec/codestream/codestream_writer.h"
#include "codec/codestream/com.h"
#include "codec/codestream/error.h"
#include "codec/codestream/jp2.h"
#include "codec/codestream/main_header.h"
#include "codec/codestream/packet_markers.h"
#include "codec/codestream/qcd.h"
#include "codec/codestream/siz.h"
#include "codec/codestream/tile_part.h"

namespace {

namespace cs = codec::cs;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(std::initializer_list<int> values) {
  Bytes out;
  for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
  return out;
}

// Appends the bytes that one writer call produces to a fresh buffer.
template <class F>
Bytes written(F&& f) {
  Bytes out;
  cs::ByteWriter w(out);
  f(w);
  return out;
}

cs::Siz simple_siz(std::uint64_t width, std::uint64_t height, unsigned components, unsigned precision) {
  cs::Siz s;
  s.xsiz = width;
  s.ysiz = height;
  s.xtsiz = width;
  s.ytsiz = height;
  s.components.assign(components, cs::SizComponent{precision, false, 1, 1});
  return s;
}

// Reversible quantization with style "none": exponent = precision + log2 of the band's gain
// (0 for LL, 1 for HL and LH, 2 for HH), the usual choice for the 5/3 path (T.800 E.1.1).
cs::Quantization reversible_quantization(unsigned precision, unsigned levels) {
  cs::Quantization q;
  q.guard_bits = 2;
  q.style = cs::QuantizationStyle::None;
  q.steps.push_back({precision, 0});
  for (unsigned l = 0; l < levels; ++l)
    for (unsigned gain : {1u, 1u, 2u}) q.steps.push_back({precision + gain, 0});
  return q;
}

// ---------------------------------------------------------------------------------------------
// ByteWriter

TEST(ByteWriter, BigEndianAndPatches) {
  Bytes out;
  cs::ByteWriter w(out);
  w.u8(0xAB);
  w.u16(0x1234);
  w.u32(0xDEADBEEF);
  w.u64(0x0102030405060708ull);
  EXPECT_EQ(out, bytes({0xAB, 0x12, 0x34, 0xDE, 0xAD, 0xBE, 0xEF, 1, 2, 3, 4, 5, 6, 7, 8}));
  w.patch_u16(1, 0xCAFE);
  w.patch_u32(3, 0x00000010);
  EXPECT_EQ(out, bytes({0xAB, 0xCA, 0xFE, 0, 0, 0, 0x10, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_THROW(w.patch_u32(12, 0), cs::CodestreamError);
  EXPECT_THROW(w.patch_u16(100, 0), cs::CodestreamError);
  w.truncate(3);
  EXPECT_EQ(out, bytes({0xAB, 0xCA, 0xFE}));
}

// ---------------------------------------------------------------------------------------------
// Marker segments, byte for byte

TEST(Siz, ThreeComponent768x512EightBit) {
  // T.800 Table A.9: Lsiz = 38 + 3 * Csiz = 47; then Rsiz, eight u32 geometry fields, Csiz and
  // per component Ssiz = depth - 1 = 7, XRsiz = YRsiz = 1.
  const Bytes expect = bytes({0xFF, 0x51, 0x00, 0x2F,                          // SIZ, Lsiz
                              0x00, 0x00,                                      // Rsiz
                              0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x02, 0x00,  // Xsiz, Ysiz
                              0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // XOsiz, YOsiz
                              0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x02, 0x00,  // XTsiz, YTsiz
                              0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // XTOsiz, YTOsiz
                              0x00, 0x03,                                      // Csiz
                              0x07, 0x01, 0x01, 0x07, 0x01, 0x01, 0x07, 0x01, 0x01});
  EXPECT_EQ(written([](cs::ByteWriter& w) { cs::write_siz(w, simple_siz(768, 512, 3, 8)); }), expect);
}

TEST(Siz, SignedSubsampledComponentAndOffsets) {
  cs::Siz s = simple_siz(20, 14, 1, 12);
  s.xosiz = 3;
  s.yosiz = 1;
  s.xtsiz = 16;
  s.ytsiz = 16;
  s.xtosiz = 2;
  s.components[0] = {12, true, 2, 3};
  const Bytes got = written([&](cs::ByteWriter& w) { cs::write_siz(w, s); });
  ASSERT_EQ(got.size(), 2u + 41u);
  EXPECT_EQ(got[3], 41);                                                  // 38 + 3
  EXPECT_EQ(Bytes(got.end() - 3, got.end()), bytes({0x8B, 0x02, 0x03}));  // signed | 11, 2, 3
  EXPECT_EQ(Bytes(got.begin() + 14, got.begin() + 22), bytes({0, 0, 0, 3, 0, 0, 0, 1}));
  EXPECT_EQ(cs::num_tiles_x(s), 2u);  // ceil((20 - 2) / 16)
  EXPECT_EQ(cs::num_tiles_y(s), 1u);
  EXPECT_EQ(cs::num_tiles(s), 2u);
}

TEST(Cod, WithPrecinctsSopEph) {
  cs::Cod c;
  c.sop = true;
  c.eph = true;
  c.order = cs::ProgressionOrder::RPCL;
  c.layers = 3;
  c.mct = true;
  c.style.levels = 2;
  c.style.xcb = 6;             // 64 wide
  c.style.ycb = 5;             // 32 high
  c.style.block_style = 0x01;  // selective arithmetic coding bypass (Table A.19)
  c.style.transform = cs::WaveletTransform::Reversible5x3;
  c.style.precincts = {{7, 7}, {8, 8}, {9, 8}};
  // Table A.12: Lcod = 12 + 3 precinct bytes; Scod = precincts | SOP | EPH = 7; SGcod = order 2,
  // layers 3, MCT 1; SPcod = 2 levels, 4, 3, style 1, transform 1, then PPy << 4 | PPx.
  const Bytes expect =
      bytes({0xFF, 0x52, 0x00, 0x0F, 0x07, 0x02, 0x00, 0x03, 0x01, 0x02, 0x04, 0x03, 0x01, 0x01, 0x77, 0x88, 0x89});
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_cod(w, c); }), expect);
}

TEST(Cod, DefaultPrecinctsLeaveScodBitClear) {
  cs::Cod c;
  c.style.levels = 5;
  c.style.transform = cs::WaveletTransform::Irreversible9x7;
  const Bytes expect = bytes({0xFF, 0x52, 0x00, 0x0C, 0x00, 0x00, 0x00, 0x01, 0x00, 0x05, 0x04, 0x04, 0x00, 0x00});
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_cod(w, c); }), expect);
}

TEST(Cod, ThirtyThreePrecinctBytesFit) {
  cs::Cod c;
  c.style.levels = 32;
  c.style.precincts.assign(33, {15, 15});
  const Bytes got = written([&](cs::ByteWriter& w) { cs::write_cod(w, c); });
  ASSERT_EQ(got.size(), 2u + 12u + 33u);
  EXPECT_EQ(got[3], 45);
  EXPECT_EQ(got.back(), 0xFF);
}

TEST(Coc, ComponentIndexWidthFollowsCsiz) {
  cs::Coc c;
  c.component = 2;
  c.style.levels = 1;
  c.style.xcb = 4;
  c.style.ycb = 4;
  c.style.precincts = {{0, 0}, {3, 4}};
  // Table A.22: Lcoc = 9 + 2 with an 8-bit Ccoc; Scoc = 1 (precincts).
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_coc(w, c, 3); }),
            bytes({0xFF, 0x53, 0x00, 0x0B, 0x02, 0x01, 0x01, 0x02, 0x02, 0x00, 0x01, 0x00, 0x43}));
  c.component = 300;
  c.style.precincts.clear();
  // Csiz >= 257: Ccoc is 16 bits and Lcoc = 10.
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_coc(w, c, 400); }),
            bytes({0xFF, 0x53, 0x00, 0x0A, 0x01, 0x2C, 0x00, 0x01, 0x02, 0x02, 0x00, 0x01}));
}

TEST(Qcd, Expounded) {
  cs::Quantization q;
  q.guard_bits = 1;
  q.style = cs::QuantizationStyle::ScalarExpounded;
  q.steps = {{8, 0}, {9, 0x7FF}, {9, 1}, {10, 0x400}};
  // Table A.27: Lqcd = 3 + 2 * 4 = 11; Sqcd = 1 << 5 | 2; SPqcd = exponent << 11 | mantissa.
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_qcd(w, q); }),
            bytes({0xFF, 0x5C, 0x00, 0x0B, 0x22, 0x40, 0x00, 0x4F, 0xFF, 0x48, 0x01, 0x54, 0x00}));
}

TEST(Qcd, NoQuantizationAndDerived) {
  // Lqcd = 4 + 3 * levels: one byte exponent << 3 per band.
  EXPECT_EQ(written([](cs::ByteWriter& w) { cs::write_qcd(w, reversible_quantization(8, 2)); }),
            bytes({0xFF, 0x5C, 0x00, 0x0A, 0x40, 0x40, 0x48, 0x48, 0x50, 0x48, 0x48, 0x50}));
  cs::Quantization d;
  d.guard_bits = 3;
  d.style = cs::QuantizationStyle::ScalarDerived;
  d.steps = {{13, 0x123}};
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_qcd(w, d); }),
            bytes({0xFF, 0x5C, 0x00, 0x05, 0x61, 0x69, 0x23}));
}

TEST(Qcc, EightAndSixteenBitComponent) {
  cs::Qcc q{1, reversible_quantization(10, 0)};
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_qcc(w, q, 3); }),
            bytes({0xFF, 0x5D, 0x00, 0x05, 0x01, 0x40, 0x50}));
  q.component = 0x1234;
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_qcc(w, q, 16384); }),
            bytes({0xFF, 0x5D, 0x00, 0x06, 0x12, 0x34, 0x40, 0x50}));
}

TEST(Qcc, MaximalExpoundedFits) {
  cs::Qcc q;
  q.component = 0;
  q.quant.style = cs::QuantizationStyle::ScalarExpounded;
  q.quant.steps.assign(cs::subband_count(32), {31, 2047});
  const Bytes got = written([&](cs::ByteWriter& w) { cs::write_qcc(w, q, 300); });
  // Lqcc = 2 (Lqcc) + 2 (Cqcc, Csiz >= 257) + 1 (Sqcc) + 2 * 97 = 7 + 6 * 32 levels.
  EXPECT_EQ(got.size(), 2u + 199u);
  EXPECT_EQ((got[2] << 8) | got[3], 199);
  EXPECT_EQ(Bytes(got.end() - 2, got.end()), bytes({0xFF, 0xFF}));
}

TEST(Qcd, SubbandSlots) {
  // LL, then HL LH HH from the coarsest level (3) to the finest (1).
  EXPECT_EQ(cs::subband_count(3), 10u);
  EXPECT_EQ(cs::subband_slot(3, 3, cs::SubbandOrientation::LL), 0u);
  EXPECT_EQ(cs::subband_slot(3, 3, cs::SubbandOrientation::HL), 1u);
  EXPECT_EQ(cs::subband_slot(3, 3, cs::SubbandOrientation::HH), 3u);
  EXPECT_EQ(cs::subband_slot(3, 2, cs::SubbandOrientation::LH), 5u);
  EXPECT_EQ(cs::subband_slot(3, 1, cs::SubbandOrientation::HH), 9u);
  EXPECT_EQ(cs::subband_slot(0, 0, cs::SubbandOrientation::LL), 0u);
  EXPECT_THROW(cs::subband_slot(3, 1, cs::SubbandOrientation::LL), cs::CodestreamError);
  EXPECT_THROW(cs::subband_slot(3, 4, cs::SubbandOrientation::HL), cs::CodestreamError);
  EXPECT_THROW(cs::subband_slot(3, 0, cs::SubbandOrientation::HL), cs::CodestreamError);
}

TEST(Com, LatinAndBinary) {
  EXPECT_EQ(written([](cs::ByteWriter& w) { cs::write_com(w, cs::latin_comment("gpuj2k")); }),
            bytes({0xFF, 0x64, 0x00, 0x0A, 0x00, 0x01, 'g', 'p', 'u', 'j', '2', 'k'}));
  cs::Comment bin{cs::CommentRegistration::Binary, {0x00, 0xFF}};
  EXPECT_EQ(written([&](cs::ByteWriter& w) { cs::write_com(w, bin); }),
            bytes({0xFF, 0x64, 0x00, 0x06, 0x00, 0x00, 0x00, 0xFF}));
}

TEST(TilePart, SotPsotSopEph) {
  Bytes out;
  cs::ByteWriter w(out);
  w.u16(0x1111);  // something before, so offsets are not 0
  const std::size_t sot = cs::write_sot(w, {5, 1, 3});
  EXPECT_EQ(sot, 2u);
  cs::write_sop(w, 65537);  // Nsop wraps modulo 65536
  w.u8(0x00);
  cs::write_eph(w);
  cs::patch_psot(w, sot);
  // Table A.4: Lsot = 10, Isot, Psot = 12 (SOT) + 6 (SOP) + 1 + 2 (EPH) = 21, TPsot, TNsot.
  EXPECT_EQ(out, bytes({0x11, 0x11, 0xFF, 0x90, 0x00, 0x0A, 0x00, 0x05, 0x00, 0x00, 0x00, 0x15,
                        0x01, 0x03, 0xFF, 0x91, 0x00, 0x04, 0x00, 0x01, 0x00, 0xFF, 0x92}));
}

TEST(CodestreamWriter, AssemblesHeaderTilePartsAndEoc) {
  cs::MainHeader h;
  h.siz = simple_siz(4, 4, 1, 8);
  h.cod.style.levels = 0;
  h.qcd = reversible_quantization(8, 0);
  h.comments.push_back(cs::latin_comment("x"));
  const Bytes body = bytes({0x00});
  const Bytes got = cs::write_codestream(h, {{0, 0, 1, body}});
  const Bytes expect =
      bytes({0xFF, 0x4F,  // SOC
             0xFF, 0x51, 0x00, 0x29, 0x00, 0x00, 0,    0,    0,    4,    0,    0,    0,    4,
             0,    0,    0,    0,    0,    0,    0,    0,  // SIZ
             0,    0,    0,    4,    0,    0,    0,    4,    0,    0,    0,    0,    0,    0,
             0,    0,    0x00, 0x01, 0x07, 0x01, 0x01,                                            //
             0xFF, 0x52, 0x00, 0x0C, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x04, 0x04, 0x00, 0x01,  // COD
             0xFF, 0x5C, 0x00, 0x04, 0x40, 0x40,                                                  // QCD
             0xFF, 0x64, 0x00, 0x05, 0x00, 0x01, 'x',                                             // COM
             0xFF, 0x90, 0x00, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0F, 0x00, 0x01,              // SOT
             0xFF, 0x93, 0x00,                                                                    // SOD, body
             0xFF, 0xD9});                                                                        // EOC
  EXPECT_EQ(got, expect);
}

// ---------------------------------------------------------------------------------------------
// JP2

// The boxes of a JP2 file: (type, content) at one nesting level.
std::vector<std::pair<std::string, Bytes>> boxes(const Bytes& data) {
  std::vector<std::pair<std::string, Bytes>> out;
  std::size_t at = 0;
  while (at + 8 <= data.size()) {
    const std::uint32_t len = (std::uint32_t{data[at]} << 24) | (std::uint32_t{data[at + 1]} << 16) |
                              (std::uint32_t{data[at + 2]} << 8) | data[at + 3];
    EXPECT_GE(len, 8u);
    EXPECT_LE(at + len, data.size());
    if (len < 8 || at + len > data.size()) break;
    out.emplace_back(std::string(data.begin() + static_cast<long>(at) + 4, data.begin() + static_cast<long>(at) + 8),
                     Bytes(data.begin() + static_cast<long>(at) + 8, data.begin() + static_cast<long>(at + len)));
    at += len;
  }
  EXPECT_EQ(at, data.size());
  return out;
}

TEST(Jp2, GreyscaleBoxes) {
  const Bytes cstream = bytes({0xFF, 0x4F, 0xFF, 0xD9});
  cs::Siz s = simple_siz(20, 14, 1, 8);
  s.xosiz = 3;
  s.yosiz = 1;
  const Bytes file = cs::wrap_jp2(cstream, cs::jp2_header_for(s));
  const auto top = boxes(file);
  ASSERT_EQ(top.size(), 4u);
  // I.5.1: 0x0000000C 'jP  ' 0x0D0A870A
  EXPECT_EQ(Bytes(file.begin(), file.begin() + 12), bytes({0, 0, 0, 12, 'j', 'P', ' ', ' ', 0x0D, 0x0A, 0x87, 0x0A}));
  EXPECT_EQ(top[1].first, "ftyp");
  EXPECT_EQ(top[1].second, bytes({'j', 'p', '2', ' ', 0, 0, 0, 0, 'j', 'p', '2', ' '}));
  EXPECT_EQ(top[2].first, "jp2h");
  EXPECT_EQ(top[3].first, "jp2c");
  EXPECT_EQ(top[3].second, cstream);
  const auto inner = boxes(top[2].second);
  ASSERT_EQ(inner.size(), 2u);
  EXPECT_EQ(inner[0].first, "ihdr");
  // HEIGHT 13, WIDTH 17, NC 1, BPC 7, C 7, UnkC 0, IPR 0 (Table I.2)
  EXPECT_EQ(inner[0].second, bytes({0, 0, 0, 13, 0, 0, 0, 17, 0, 1, 7, 7, 0, 0}));
  EXPECT_EQ(inner[1].first, "colr");
  EXPECT_EQ(inner[1].second, bytes({1, 0, 0, 0, 0, 0, 17}));  // enumerated greyscale
}

TEST(Jp2, RgbaWithMixedDepthsHasBpccAndCdef) {
  cs::Jp2Header h;
  h.width = 5;
  h.height = 7;
  h.components = {{16, false}, {16, false}, {16, false}, {8, true}};
  const auto top = boxes(cs::wrap_jp2({}, h));
  ASSERT_EQ(top.size(), 4u);
  const auto inner = boxes(top[2].second);
  ASSERT_EQ(inner.size(), 4u);
  EXPECT_EQ(inner[0].first, "ihdr");
  EXPECT_EQ(inner[0].second, bytes({0, 0, 0, 7, 0, 0, 0, 5, 0, 4, 255, 7, 0, 0}));
  EXPECT_EQ(inner[1].first, "bpcc");
  EXPECT_EQ(inner[1].second, bytes({15, 15, 15, 0x87}));
  EXPECT_EQ(inner[2].first, "colr");
  EXPECT_EQ(inner[2].second, bytes({1, 0, 0, 0, 0, 0, 16}));  // enumerated sRGB
  EXPECT_EQ(inner[3].first, "cdef");
  // N = 4; (Cn, Typ, Asoc): colours associated with colours 1..3, opacity with the whole image.
  EXPECT_EQ(inner[3].second, bytes({0, 4, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 2, 0, 2, 0, 0, 0, 3, 0, 3, 0, 1, 0, 0}));
  EXPECT_TRUE(top[3].second.empty());
}

TEST(Jp2, GreyAlphaCdef) {
  cs::Jp2Header h{3, 3, {{8, false}, {8, false}}, {}, {}};
  const auto inner = boxes(boxes(cs::wrap_jp2({}, h))[2].second);
  ASSERT_EQ(inner.size(), 3u);
  EXPECT_EQ(inner[1].second, bytes({1, 0, 0, 0, 0, 0, 17}));
  EXPECT_EQ(inner[2].second, bytes({0, 2, 0, 0, 0, 0, 0, 1, 0, 1, 0, 1, 0, 0}));
}

// The resolution box follows the other header boxes: capture, then display, each VR N, D, HR N, D,
// VR E, HR E (T.800 I.5.3.7), the fractions as close as 16-bit terms allow.
TEST(Jp2, ResolutionBox) {
  cs::Jp2Header h{3, 3, {{8, false}, {8, false}, {8, false}}, {2000, 3780.5}, {}};
  const auto inner = boxes(boxes(cs::wrap_jp2({}, h))[2].second);
  ASSERT_EQ(inner.size(), 3u);
  EXPECT_EQ(inner[2].first, "res ");
  const auto res = boxes(inner[2].second);
  ASSERT_EQ(res.size(), 1u);
  EXPECT_EQ(res[0].first, "resc");
  // 2000 = 2000 / 1 and 3780.5 = 7561 / 2, both with exponent 0: exact.
  EXPECT_EQ(res[0].second, bytes({0x07, 0xD0, 0, 1, 0x1D, 0x89, 0, 2, 0, 0}));
  h.display = {72, 1e9};
  const auto both = boxes(boxes(boxes(cs::wrap_jp2({}, h))[2].second)[2].second);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].first, "resd");

  for (const double v : {1.0, 72.0, 2834.645669, 3779.527559, 12345.678, 65535.0, 65536.0, 1e-3, 3.1e7, 6.5535e131}) {
    const cs::Jp2ResolutionFraction f = cs::resolution_fraction(v);
    ASSERT_GT(f.denominator, 0);
    const double back = f.numerator / static_cast<double>(f.denominator) * std::pow(10.0, f.exponent);
    EXPECT_NEAR(back / v, 1.0, 1e-5) << v;
  }
  for (const double bad : {0.0, -1.0, std::nan(""), 1e200})
    EXPECT_THROW(cs::resolution_fraction(bad), cs::CodestreamError);
}

TEST(Jp2, Rejects) {
  EXPECT_THROW(cs::wrap_jp2({}, cs::Jp2Header{1, 1, {}, {}, {}}), cs::CodestreamError);
  EXPECT_THROW(cs::wrap_jp2({}, cs::Jp2Header{1, 1, std::vector<cs::Jp2Component>(5), {}, {}}), cs::CodestreamError);
  EXPECT_THROW(cs::wrap_jp2({}, cs::Jp2Header{0, 1, {{8, false}}, {}, {}}), cs::CodestreamError);
  EXPECT_THROW(cs::wrap_jp2({}, cs::Jp2Header{1, 1, {{39, false}}, {}, {}}), cs::CodestreamError);
}

// ---------------------------------------------------------------------------------------------
// Validation

// The message of the CodestreamError `f` throws; fails the test if it throws nothing.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const cs::CodestreamError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no CodestreamError";
  return {};
}

void expect_siz_error(const cs::Siz& s, const std::string& fragment) {
  const std::string msg = error_of([&] { cs::validate_siz(s); });
  EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(Validation, Siz) {
  const cs::Siz ok = simple_siz(17, 13, 1, 8);
  EXPECT_NO_THROW(cs::validate_siz(ok));
  cs::Siz s = ok;
  s.xosiz = 17;
  expect_siz_error(s, "XOsiz");
  s = ok;
  s.yosiz = 20;
  expect_siz_error(s, "YOsiz");
  s = ok;
  s.xosiz = 4;
  s.xtosiz = 5;
  expect_siz_error(s, "XTOsiz");
  s = ok;
  s.xosiz = 8;
  s.xtsiz = 8;  // tile [0, 8) does not reach the image at x = 8
  expect_siz_error(s, "first tile");
  s = ok;
  s.yosiz = 4;
  s.ytsiz = 2;
  s.ytosiz = 1;
  expect_siz_error(s, "YTOsiz + YTsiz");
  s = ok;
  s.xsiz = 0x100000000ull;
  expect_siz_error(s, "Xsiz");
  s = ok;
  s.ytsiz = 0;
  expect_siz_error(s, "YTsiz");
  s = ok;
  s.components.clear();
  expect_siz_error(s, "Csiz");
  s = ok;
  s.components.assign(16385, {});
  expect_siz_error(s, "Csiz");
  s = ok;
  s.components[0].precision = 39;
  expect_siz_error(s, "precision");
  s = ok;
  s.components[0].precision = 0;
  expect_siz_error(s, "precision");
  s = ok;
  s.components[0].xrsiz = 256;
  expect_siz_error(s, "XRsiz");
  s = ok;
  s.components[0].yrsiz = 0;
  expect_siz_error(s, "YRsiz");
  s = simple_siz(1000, 1000, 1, 8);
  s.xtsiz = 1;
  s.ytsiz = 1;
  expect_siz_error(s, "65535");
  // Largest legal values pass.
  s = simple_siz(0xFFFFFFFFull, 0xFFFFFFFFull, 16384, 38);
  EXPECT_NO_THROW(cs::validate_siz(s));
}

TEST(Validation, CodingStyle) {
  auto cod_error = [](auto mutate) {
    cs::Cod c;
    mutate(c);
    return error_of([&] { cs::validate_cod(c); });
  };
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.levels = 33; }).find("32"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.xcb = 1; }).find("2..10"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.ycb = 11; }).find("2..10"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.xcb = 7, c.style.ycb = 6; }).find("12"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.layers = 0; }).find("layers"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.layers = 65536; }).find("layers"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.order = static_cast<cs::ProgressionOrder>(5); }).find("progression"),
            std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.transform = static_cast<cs::WaveletTransform>(2); }).find("transform"),
            std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) { c.style.precincts.assign(5, {}); }).find("resolutions"), std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) {
              c.style.levels = 1;
              c.style.precincts = {{0, 0}, {0, 4}};
            }).find("resolution 1"),
            std::string::npos);
  EXPECT_NE(cod_error([](cs::Cod& c) {
              c.style.levels = 0;
              c.style.precincts = {{16, 1}};
            }).find("15"),
            std::string::npos);
  // 0 is fine at resolution 0, and 2^10 x 2^2 blocks are fine.
  cs::Cod c;
  c.style.levels = 1;
  c.style.precincts = {{0, 0}, {1, 1}};
  c.style.xcb = 10;
  c.style.ycb = 2;
  EXPECT_NO_THROW(cs::validate_cod(c));
  cs::Coc coc{3, {}};
  EXPECT_THROW(cs::validate_coc(coc, 3), cs::CodestreamError);
  EXPECT_NO_THROW(cs::validate_coc(coc, 4));
}

TEST(Validation, Quantization) {
  cs::Quantization q = reversible_quantization(8, 1);
  q.guard_bits = 8;
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q = reversible_quantization(8, 1);
  q.steps.pop_back();
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q = reversible_quantization(8, 1);
  q.steps[0].exponent = 32;
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q = reversible_quantization(8, 1);
  q.steps[0].mantissa = 1;  // "none" has no mantissa
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q.style = cs::QuantizationStyle::ScalarExpounded;
  q.steps[0].mantissa = 2048;
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q.style = cs::QuantizationStyle::ScalarDerived;
  q.steps.assign(2, {});
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  q.style = cs::QuantizationStyle::ScalarExpounded;
  q.steps.assign(100, {});  // 3 * 33 + 1: one level too many
  EXPECT_THROW(cs::validate_quantization(q, "QCD"), cs::CodestreamError);
  cs::Qcc qcc{1, reversible_quantization(8, 0)};
  EXPECT_THROW(cs::validate_qcc(qcc, 1), cs::CodestreamError);
}

TEST(Validation, OversizedCommentLeavesNothingBehind) {
  Bytes out = bytes({0x42});
  cs::ByteWriter w(out);
  cs::Comment c;
  c.data.assign(65532, 'a');
  EXPECT_THROW(cs::write_com(w, c), cs::CodestreamError);
  EXPECT_EQ(out, bytes({0x42}));
  c.data.pop_back();
  cs::write_com(w, c);
  EXPECT_EQ(out.size(), 1u + 2u + 65535u);
  EXPECT_EQ(out[3], 0xFF);
  EXPECT_EQ(out[4], 0xFF);
}

cs::MainHeader rgb_header() {
  cs::MainHeader h;
  h.siz = simple_siz(8, 8, 3, 8);
  h.cod.mct = true;
  h.cod.style.levels = 2;
  h.qcd = reversible_quantization(8, 2);
  return h;
}

TEST(Validation, MainHeaderRelations) {
  EXPECT_NO_THROW(cs::validate_main_header(rgb_header()));

  cs::MainHeader h = rgb_header();
  h.qcd = reversible_quantization(8, 3);
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("component 0"), std::string::npos);

  // A COC changing the level count needs a QCC to match it.
  h = rgb_header();
  h.cod.mct = false;
  h.cocs.push_back({2, h.cod.style});
  h.cocs.back().style.levels = 4;
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("needs 13 step sizes"), std::string::npos);
  h.qccs.push_back({2, reversible_quantization(8, 4)});
  EXPECT_NO_THROW(cs::validate_main_header(h));
  h.qccs.push_back({2, reversible_quantization(8, 4)});
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("twice"), std::string::npos);

  h = rgb_header();
  h.cocs = {{1, h.cod.style}, {1, h.cod.style}};
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("twice"), std::string::npos);

  // Derived quantization carries one step whatever the level count.
  h = rgb_header();
  h.qcd.style = cs::QuantizationStyle::ScalarDerived;
  h.qcd.steps = {{8, 0}};
  EXPECT_NO_THROW(cs::validate_main_header(h));

  h = rgb_header();
  h.siz.components.pop_back();
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("at least 3"), std::string::npos);
  h = rgb_header();
  h.siz.components[1].xrsiz = 2;
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("subsampled"), std::string::npos);
  h = rgb_header();
  h.cocs.push_back({2, h.cod.style});
  h.cocs.back().style.transform = cs::WaveletTransform::Irreversible9x7;
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("filter"), std::string::npos);
  h = rgb_header();
  h.cocs.push_back({1, h.cod.style});
  h.cocs.back().style.levels = 3;
  h.qccs.push_back({1, reversible_quantization(8, 3)});
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("level count"), std::string::npos);
  h.cod.mct = false;  // fine without the transform
  EXPECT_NO_THROW(cs::validate_main_header(h));
  h.cod.mct = true;

  // Nothing is written when validation fails.
  Bytes out;
  cs::ByteWriter w(out);
  EXPECT_THROW(cs::write_main_header(w, h), cs::CodestreamError);
  EXPECT_TRUE(out.empty());
}

TEST(Validation, TilePartSequencing) {
  cs::MainHeader h = rgb_header();
  h.siz.xtsiz = 4;  // 2 x 2 tiles
  h.siz.ytsiz = 4;
  cs::CodestreamWriter w(h);
  EXPECT_EQ(w.num_tiles(), 4u);
  const Bytes body = bytes({0});
  EXPECT_THROW(w.add_tile_part(4, 0, 1, body), cs::CodestreamError);  // no tile 4
  EXPECT_THROW(w.add_tile_part(0, 1, 2, body), cs::CodestreamError);  // part 1 before part 0
  EXPECT_THROW(w.add_tile_part(0, 2, 2, body), cs::CodestreamError);  // TPsot >= TNsot
  EXPECT_THROW(w.add_tile_part(0, 0, 256, body), cs::CodestreamError);
  w.add_tile_part(0, 0, 2, body);
  EXPECT_THROW(w.add_tile_part(0, 1, 3, body), cs::CodestreamError);  // TNsot changed
  w.add_tile_part(1, 0, 1, body);
  w.add_tile_part(0, 1, 0, body);  // 0: not signalled here
  w.add_tile_part(3, 0, 1, body);
  EXPECT_NE(error_of([&] { w.finish(); }).find("tile 2"), std::string::npos);
  w.add_tile_part(2, 0, 0, body);
  EXPECT_THROW(w.add_tile_part(2, 0, 1, body), cs::CodestreamError);  // part 0 again
  const Bytes out = w.finish();
  EXPECT_EQ(Bytes(out.end() - 2, out.end()), bytes({0xFF, 0xD9}));
  EXPECT_THROW(w.finish(), cs::CodestreamError);
  EXPECT_THROW(w.add_tile_part(2, 1, 0, body), cs::CodestreamError);

  cs::CodestreamWriter short_tile(rgb_header());
  short_tile.add_tile_part(0, 0, 2, body);
  EXPECT_NE(error_of([&] { short_tile.finish(); }).find("declares 2"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// End to end: codestreams whose packets are all empty, decoded by OpenJPEG and Grok.
//
// A packet whose first header bit is 0 is a zero-length packet (T.800 B.10.3); with byte
// alignment the whole header is one 0x00 byte. If every packet is empty, every coefficient is 0 and
// the decoder reconstructs the DC level shift, 2^(precision-1), for unsigned components. Getting
// the decoders to accept such a stream checks the markers and the packet count, which depends on
// the tile, component, resolution and precinct geometry of T.800 B.5 and B.6.

std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) { return (a + b - 1) / b; }

// Number of packets a tile has: layers x the sum over components and resolutions of the precincts
// (T.800 B.6). A resolution with no samples has no precincts, hence no packets.
std::uint64_t packets_in_tile(const cs::MainHeader& h, unsigned tile) {
  const cs::Siz& s = h.siz;
  const unsigned p = tile % cs::num_tiles_x(s);
  const unsigned q = tile / cs::num_tiles_x(s);
  // B-7: the tile on the reference grid.
  const std::uint64_t tx0 = std::max(s.xtosiz + p * s.xtsiz, s.xosiz);
  const std::uint64_t ty0 = std::max(s.ytosiz + q * s.ytsiz, s.yosiz);
  const std::uint64_t tx1 = std::min(s.xtosiz + (p + 1) * s.xtsiz, s.xsiz);
  const std::uint64_t ty1 = std::min(s.ytosiz + (q + 1) * s.ytsiz, s.ysiz);
  std::uint64_t precincts = 0;
  for (unsigned c = 0; c < s.components.size(); ++c) {
    // B-12: the tile-component.
    const std::uint64_t tcx0 = ceil_div(tx0, s.components[c].xrsiz), tcx1 = ceil_div(tx1, s.components[c].xrsiz);
    const std::uint64_t tcy0 = ceil_div(ty0, s.components[c].yrsiz), tcy1 = ceil_div(ty1, s.components[c].yrsiz);
    const cs::CodingStyle& style = cs::coding_style_for(h, c);
    for (unsigned r = 0; r <= style.levels; ++r) {
      // B-14: resolution r of NL sits at a scale of 2^(NL - r).
      const std::uint64_t scale = std::uint64_t{1} << (style.levels - r);
      const std::uint64_t trx0 = ceil_div(tcx0, scale), trx1 = ceil_div(tcx1, scale);
      const std::uint64_t try0 = ceil_div(tcy0, scale), try1 = ceil_div(tcy1, scale);
      const cs::PrecinctSize pp = style.precincts.empty() ? cs::PrecinctSize{15, 15} : style.precincts[r];
      // B-16
      const std::uint64_t wide = trx1 > trx0 ? ceil_div(trx1, std::uint64_t{1} << pp.ppx) - (trx0 >> pp.ppx) : 0;
      const std::uint64_t high = try1 > try0 ? ceil_div(try1, std::uint64_t{1} << pp.ppy) - (try0 >> pp.ppy) : 0;
      precincts += wide * high;
    }
  }
  return precincts * h.cod.layers;
}

TEST(PacketGeometry, CountsFromTileAndPrecincts) {
  // 17x13 image at (3, 1), 16x16 tiles from (2, 0): tile 0 covers x 3..17, tile 1 x 18..19.
  cs::MainHeader h;
  h.siz = simple_siz(20, 14, 1, 8);
  h.siz.xosiz = 3;
  h.siz.yosiz = 1;
  h.siz.xtsiz = 16;
  h.siz.ytsiz = 16;
  h.siz.xtosiz = 2;
  h.cod.style.levels = 3;
  ASSERT_EQ(cs::num_tiles(h.siz), 2u);
  EXPECT_EQ(packets_in_tile(h, 0), 4u);
  // Tile 1 is 2 wide starting at x = 18: at resolutions 0 and 1 (scale 8, 4) it is empty, since
  // ceil(18/8) = ceil(20/8) and ceil(18/4) = ceil(20/4), so it has packets only for r = 2 and 3.
  EXPECT_EQ(packets_in_tile(h, 1), 2u);
  h.cod.style.precincts = {{1, 1}, {1, 1}, {1, 1}, {1, 1}};
  // 2x2 precincts: r = 2 spans x 9..10, y 1..7 (1 x 4 precincts); r = 3 x 18..20, y 1..14 (1 x 7).
  EXPECT_EQ(packets_in_tile(h, 1), 4u + 7u);
}

// Directory removed with its contents when the test ends, unless CODESTREAM_TEST_KEEP is set
// (then its path is printed, to look at the files the decoders were given).
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "codestream_test_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    if (std::getenv("CODESTREAM_TEST_KEEP")) {
      std::printf("kept %s\n", path_.c_str());
      return;
    }
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// Runs a command, its output going to `log`; returns its exit status and the log's text.
std::pair<int, std::string> run(const std::string& command, const std::string& log) {
  const int status = std::system((command + " >" + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

void write_file(const std::string& path, const Bytes& data) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  ASSERT_TRUE(out.good()) << path;
}

// A decoded Netpbm image (P5 greyscale, P6 RGB, P7 PAM), samples interleaved.
struct Netpbm {
  unsigned width = 0, height = 0, depth = 0, maxval = 0;
  std::vector<unsigned> samples;
};

// Reads the small Netpbm files the decoders write. Samples wider than a byte are big-endian.
bool read_netpbm(const std::string& path, Netpbm& img, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return error = "cannot open " + path, false;
  std::string magic;
  in >> magic;
  if (magic == "P5" || magic == "P6") {
    img.depth = magic == "P5" ? 1 : 3;
    // Header: width height maxval, whitespace-separated, '#' comments allowed, one whitespace byte
    // before the raster.
    unsigned* fields[] = {&img.width, &img.height, &img.maxval};
    for (unsigned* f : fields) {
      in >> std::ws;
      while (in.peek() == '#') {
        std::string comment;
        std::getline(in, comment);
        in >> std::ws;
      }
      in >> *f;
    }
    in.get();
  } else if (magic == "P7") {
    std::string key;
    while (in >> key && key != "ENDHDR") {
      if (key == "WIDTH")
        in >> img.width;
      else if (key == "HEIGHT")
        in >> img.height;
      else if (key == "DEPTH")
        in >> img.depth;
      else if (key == "MAXVAL")
        in >> img.maxval;
      else {
        std::string rest;
        std::getline(in, rest);
      }
    }
    in.get();
  } else {
    return error = path + ": not P5/P6/P7 but '" + magic + "'", false;
  }
  if (!in || img.width == 0 || img.height == 0 || img.depth == 0 || img.maxval == 0 || img.maxval > 65535)
    return error = path + ": bad header", false;
  const std::size_t n = std::size_t{img.width} * img.height * img.depth;
  const unsigned bytes_per = img.maxval > 255 ? 2 : 1;
  std::vector<char> raster(n * bytes_per);
  in.read(raster.data(), static_cast<std::streamsize>(raster.size()));
  if (static_cast<std::size_t>(in.gcount()) != raster.size()) return error = path + ": truncated raster", false;
  img.samples.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned>(static_cast<unsigned char>(raster[k])); };
    img.samples[i] = bytes_per == 2 ? (b(2 * i) << 8) | b(2 * i + 1) : b(i);
  }
  return true;
}

// A decoded image as the decoders write it, samples of all components.
struct Decoded {
  unsigned width = 0, height = 0, components = 0;
  bool planar = false;  // component planes one after another, else interleaved per pixel
  std::vector<long> samples;
};

// PGX (one component per file): "PG ML|LM +|- depth width height\n", then samples of 1, 2 or 4
// bytes as the depth needs, in the byte order the header names, two's complement when signed.
bool read_pgx(const std::string& path, Decoded& img, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  std::string magic, order, sign;
  unsigned depth = 0;
  in >> magic >> order >> sign >> depth >> img.width >> img.height;
  in.get();
  if (!in || magic != "PG" || (order != "ML" && order != "LM") || (sign != "+" && sign != "-") || depth < 1 ||
      depth > 32)
    return error = path + ": bad PGX header", false;
  img.components = 1;
  const unsigned bytes_per = depth <= 8 ? 1 : depth <= 16 ? 2 : 4;
  const std::size_t n = std::size_t{img.width} * img.height;
  std::vector<unsigned char> data(n * bytes_per);
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (static_cast<std::size_t>(in.gcount()) != data.size()) return error = path + ": truncated PGX", false;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t v = 0;
    for (unsigned k = 0; k < bytes_per; ++k) {
      const unsigned byte = data[i * bytes_per + (order == "ML" ? k : bytes_per - 1 - k)];
      v = (v << 8) | byte;
    }
    const unsigned bits = 8 * bytes_per;
    long value = static_cast<long>(v);
    if (sign == "-" && (v >> (bits - 1)) != 0) value -= static_cast<long>(std::uint64_t{1} << bits);
    img.samples.push_back(value);
  }
  return true;
}

// Big-endian raw output: every component's plane in turn, 2 bytes per sample above 8 bits.
bool read_raw_be(const std::string& path, const cs::Siz& siz, Decoded& img, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  img.width = static_cast<unsigned>(siz.xsiz - siz.xosiz);
  img.height = static_cast<unsigned>(siz.ysiz - siz.yosiz);
  img.components = static_cast<unsigned>(siz.components.size());
  img.planar = true;
  const unsigned bytes_per = siz.components[0].precision > 8 ? 2 : 1;
  const std::size_t n = std::size_t{img.width} * img.height * img.components;
  if (data.size() != n * bytes_per)
    return error = path + ": " + std::to_string(data.size()) + " bytes, expected " + std::to_string(n * bytes_per),
           false;
  const auto b = [&](std::size_t k) { return static_cast<unsigned>(static_cast<unsigned char>(data[k])); };
  for (std::size_t i = 0; i < n; ++i) img.samples.push_back(bytes_per == 2 ? (b(2 * i) << 8) | b(2 * i + 1) : b(i));
  return true;
}

struct EmptyCase {
  std::string name;
  cs::MainHeader header;
  bool jp2 = false;
  unsigned parts_per_tile = 1;  // packets split evenly over this many tile-parts
};

// The output format each decoder is asked for. Greyscale and RGB go to PGM and PPM, signed
// greyscale to PGX. With 4
// components the decoders disagree: opj_decompress 2.5.0 writes them to .pnm as a P7 (PAM) RGB_ALPHA
// file but rejects a .pam name, and its .raw is little-endian despite its help text; Grok 10.0.5
// drops the alpha channel from .pam/.pnm but writes all four, big-endian, to .raw.
std::string output_extension(const std::string& decoder, const EmptyCase& c) {
  if (c.header.siz.components[0].is_signed) return "pgx";  // Netpbm has no signed samples
  switch (c.header.siz.components.size()) {
    case 1:
      return "pgm";
    case 3:
      return "ppm";
    default:
      return decoder == "opj_decompress" ? "pnm" : "raw";
  }
}

// gtest prints a failing parameter with this instead of its bytes.
void PrintTo(const EmptyCase& c, std::ostream* os) { *os << c.name; }

// The codestream (or JP2 file) of empty packets for a header, one packet per 0x00 byte plus SOP
// and EPH when the COD asks for them.
Bytes empty_codestream(const EmptyCase& c) {
  const cs::MainHeader& h = c.header;
  cs::CodestreamWriter writer(h);
  for (unsigned t = 0; t < writer.num_tiles(); ++t) {
    const std::uint64_t packets = packets_in_tile(h, t);
    std::uint64_t next = 0;
    for (unsigned part = 0; part < c.parts_per_tile; ++part) {
      const std::uint64_t end = packets * (part + 1) / c.parts_per_tile;
      Bytes body;
      cs::ByteWriter w(body);
      for (; next < end; ++next) {
        if (h.cod.sop) cs::write_sop(w, next);
        w.u8(0x00);
        if (h.cod.eph) cs::write_eph(w);
      }
      writer.add_tile_part(t, part, c.parts_per_tile, body);
    }
  }
  Bytes out = writer.finish();
  return c.jp2 ? cs::wrap_jp2(out, cs::jp2_header_for(h.siz)) : out;
}

void expect_dc_level(const EmptyCase& c, const std::string& path) {
  const cs::Siz& s = c.header.siz;
  Decoded img;
  std::string error;
  if (path.ends_with(".raw")) {
    ASSERT_TRUE(read_raw_be(path, s, img, error)) << error;
  } else if (path.ends_with(".pgx")) {
    // Both decoders append the component index to a PGX name: x.pgx becomes x_0.pgx.
    ASSERT_TRUE(read_pgx(path.substr(0, path.size() - 4) + "_0.pgx", img, error)) << error;
  } else {
    Netpbm pnm;
    ASSERT_TRUE(read_netpbm(path, pnm, error)) << error;
    img = Decoded{pnm.width, pnm.height, pnm.depth, false, {pnm.samples.begin(), pnm.samples.end()}};
  }
  EXPECT_EQ(img.width, s.xsiz - s.xosiz);
  EXPECT_EQ(img.height, s.ysiz - s.yosiz);
  ASSERT_EQ(img.components, s.components.size()) << path;
  const std::size_t plane = std::size_t{img.width} * img.height;
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < img.samples.size(); ++i) {
    const cs::SizComponent& comp = s.components[img.planar ? i / plane : i % img.components];
    const long expect = comp.is_signed ? 0 : 1L << (comp.precision - 1);
    if (img.samples[i] != expect && wrong++ < 5)
      ADD_FAILURE() << path << ": sample " << i << " is " << img.samples[i] << ", expected " << expect;
  }
  EXPECT_EQ(wrong, 0u) << path;
}

class EmptyPackets : public ::testing::TestWithParam<EmptyCase> {};

TEST_P(EmptyPackets, DecodeToDcLevel) {
  const EmptyCase& c = GetParam();
  TempDir dir;
  const std::string input = dir.file(c.name + (c.jp2 ? ".jp2" : ".j2k"));
  write_file(input, empty_codestream(c));

  const std::vector<std::string> decoders = {"opj_decompress", "grk_decompress"};
  for (const std::string& decoder : decoders)
    if (!on_path(decoder)) GTEST_SKIP() << decoder << " is not on PATH (Debian: libopenjp2-tools, grokj2k-tools)";

  for (const std::string& decoder : decoders) {
    const std::string output = dir.file(decoder + "." + output_extension(decoder, c));
    const auto [status, log] = run(decoder + " -i " + input + " -o " + output, dir.file(decoder + ".log"));
    ASSERT_EQ(status, 0) << decoder << " failed on " << c.name << ":\n" << log;
    expect_dc_level(c, output);
  }

  if (!c.jp2) return;
  // The file format itself: OpenJPEG writes the JP2 to PNG, and its dump sees every component.
  const std::string png = dir.file("opj.png");
  const auto [png_status, png_log] = run("opj_decompress -i " + input + " -o " + png, dir.file("png.log"));
  EXPECT_EQ(png_status, 0) << png_log;
  EXPECT_TRUE(std::filesystem::exists(png));
  if (!on_path("opj_dump")) GTEST_SKIP() << "opj_dump is not on PATH (Debian: libopenjp2-tools)";
  const auto [dump_status, dump] = run("opj_dump -i " + input, dir.file("dump.log"));
  EXPECT_EQ(dump_status, 0) << dump;
  const std::string numcomps = "numcomps=" + std::to_string(c.header.siz.components.size());
  EXPECT_NE(dump.find(numcomps), std::string::npos) << dump;
}

std::vector<EmptyCase> empty_cases() {
  std::vector<EmptyCase> cases;

  {  // greyscale 8-bit 17x13, 3 levels
    EmptyCase c{"grey8_17x13_l3", {}, false, 1};
    c.header.siz = simple_siz(17, 13, 1, 8);
    c.header.cod.style.levels = 3;
    c.header.qcd = reversible_quantization(8, 3);
    cases.push_back(c);
  }
  {  // RGB 8-bit 33x20, 2 levels, 2 layers, RCT
    EmptyCase c{"rgb8_33x20_l2_2layers", {}, false, 1};
    c.header.siz = simple_siz(33, 20, 3, 8);
    c.header.cod.layers = 2;
    c.header.cod.mct = true;
    c.header.cod.style.levels = 2;
    c.header.qcd = reversible_quantization(8, 2);
    cases.push_back(c);
  }
  {  // RGBA 16-bit 5x7, no decomposition, in JP2
    EmptyCase c{"rgba16_5x7_l0_jp2", {}, true, 1};
    c.header.siz = simple_siz(5, 7, 4, 16);
    c.header.cod.style.levels = 0;
    c.header.qcd = reversible_quantization(16, 0);
    cases.push_back(c);
  }
  // Two tiles of a 17x13 image whose origin is off the tile grid's: tile 1 is only two columns wide
  // and has no samples at resolutions 0 and 1.
  const auto two_tiles = [](unsigned components, unsigned precision, unsigned levels) {
    cs::MainHeader h;
    h.siz = simple_siz(20, 14, components, precision);
    h.siz.xosiz = 3;
    h.siz.yosiz = 1;
    h.siz.xtsiz = 16;
    h.siz.ytsiz = 16;
    h.siz.xtosiz = 2;
    h.siz.ytosiz = 0;
    h.cod.style.levels = levels;
    h.qcd = reversible_quantization(precision, levels);
    return h;
  };
  cases.push_back({"grey8_two_tiles_l3", two_tiles(1, 8, 3), false, 1});
  cases.push_back({"rgba16_two_tiles_l0_jp2", two_tiles(4, 16, 0), true, 1});
  cases.push_back({"rgba16_two_tiles_l2_jp2", two_tiles(4, 16, 2), true, 1});
  {  // the same with small precincts, SOP and EPH, RPCL, 3 layers and two tile-parts per tile
    EmptyCase c{"grey8_two_tiles_precincts_sop_eph", two_tiles(1, 8, 3), false, 2};
    c.header.cod.sop = true;
    c.header.cod.eph = true;
    c.header.cod.order = cs::ProgressionOrder::RPCL;
    c.header.cod.layers = 3;
    c.header.cod.style.precincts = {{0, 1}, {1, 1}, {2, 1}, {2, 3}};
    cases.push_back(c);
  }
  {  // 12-bit greyscale, PCRL, 5 levels on a 17x13 image (the coarsest resolutions are 1x1)
    EmptyCase c{"grey12_l5_pcrl", {}, false, 1};
    c.header.siz = simple_siz(17, 13, 1, 12);
    c.header.cod.order = cs::ProgressionOrder::PCRL;
    c.header.cod.style.levels = 5;
    c.header.qcd = reversible_quantization(12, 5);
    cases.push_back(c);
  }
  {  // signed 12-bit greyscale: reconstructs to 0, there is no level shift
    EmptyCase c{"grey_signed12_l2", {}, false, 1};
    c.header.siz = simple_siz(17, 13, 1, 12);
    c.header.siz.components[0].is_signed = true;
    c.header.cod.style.levels = 2;
    c.header.qcd = reversible_quantization(12, 2);
    cases.push_back(c);
  }
  {  // irreversible 9/7 with ICT; COC and QCC give component 2 other code-blocks, precincts and
     // derived quantization
    EmptyCase c{"rgb8_97_ict_coc_qcc", {}, false, 1};
    c.header.siz = simple_siz(33, 20, 3, 8);
    c.header.cod.mct = true;
    c.header.cod.order = cs::ProgressionOrder::RLCP;
    c.header.cod.style.levels = 2;
    c.header.cod.style.transform = cs::WaveletTransform::Irreversible9x7;
    c.header.qcd.style = cs::QuantizationStyle::ScalarExpounded;
    c.header.qcd.steps.assign(cs::subband_count(2), {9, 100});
    cs::CodingStyle other = c.header.cod.style;
    other.xcb = 5;
    other.ycb = 4;
    other.precincts = {{2, 2}, {3, 2}, {4, 4}};
    c.header.cocs.push_back({2, other});
    cs::Quantization derived;
    derived.style = cs::QuantizationStyle::ScalarDerived;
    derived.steps = {{8, 0}};
    c.header.qccs.push_back({2, derived});
    c.header.comments.push_back(cs::latin_comment("empty packets"));
    cases.push_back(c);
  }
  {  // three components without a colour transform, each with its own level count, CPRL
    EmptyCase c{"three_comp_levels_cprl", {}, false, 1};
    c.header.siz = simple_siz(33, 20, 3, 8);
    c.header.cod.order = cs::ProgressionOrder::CPRL;
    c.header.cod.style.levels = 2;
    c.header.qcd = reversible_quantization(8, 2);
    for (unsigned comp : {1u, 2u}) {
      cs::CodingStyle s = c.header.cod.style;
      s.levels = comp == 1 ? 0 : 4;
      c.header.cocs.push_back({comp, s});
      c.header.qccs.push_back({comp, reversible_quantization(8, s.levels)});
    }
    cases.push_back(c);
  }
  // Each again with SOP and EPH markers. Decoders read a missing trailing packet as empty, so a
  // packet count one too low goes unnoticed, except that a packet that must end in EPH cannot be
  // missing: OpenJPEG then fails with "Not enough space for required EPH marker".
  const std::size_t plain = cases.size();
  for (std::size_t i = 0; i < plain; ++i) {
    if (cases[i].header.cod.sop || cases[i].header.cod.eph) continue;
    EmptyCase c = cases[i];
    c.name += "_sop_eph";
    c.header.cod.sop = true;
    c.header.cod.eph = true;
    cases.push_back(c);
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Decoders, EmptyPackets, ::testing::ValuesIn(empty_cases()),
                         [](const ::testing::TestParamInfo<EmptyCase>& info) { return info.param.name; });

}  // namespace

namespace {

// Part 15 (T.814 A.3): a CAP segment with Pcap's Part 15 bit and Ccap15 right after the SIZ, and
// only with Rsiz bit 14; Ccap15's MAGB field follows the largest Mb.
TEST(Cap, HtOnlyCapabilitiesAfterSiz) {
  EXPECT_EQ(cs::ht_only_ccap15(false, 8), 0x0000);
  EXPECT_EQ(cs::ht_only_ccap15(false, 9), 0x0001);
  EXPECT_EQ(cs::ht_only_ccap15(true, 19), 0x0020 | 11);
  EXPECT_EQ(cs::ht_only_ccap15(false, 27), 19);
  EXPECT_EQ(cs::ht_only_ccap15(false, 28), 13 + 7);
  EXPECT_EQ(cs::ht_only_ccap15(false, 47), 13 + 11);
  EXPECT_EQ(cs::ht_only_ccap15(false, 48), 31);

  cs::MainHeader h = rgb_header();
  h.ccap15 = cs::ht_only_ccap15(false, 10);
  EXPECT_NE(error_of([&] { cs::validate_main_header(h); }).find("Rsiz bit 14"), std::string::npos);
  h.siz.rsiz = cs::kRsizCapabilitiesInCap;
  std::vector<std::uint8_t> out;
  cs::ByteWriter w(out);
  cs::write_main_header(w, h);
  const std::size_t cap = 4 + (static_cast<std::size_t>(out[4]) << 8 | out[5]);
  EXPECT_EQ(out[6], 0x40);
  const std::vector<std::uint8_t> expected = {0xFF, 0x50, 0x00, 0x08, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02};
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin() + static_cast<std::ptrdiff_t>(cap),
                                      out.begin() + static_cast<std::ptrdiff_t>(cap) + 10),
            expected);
  EXPECT_EQ(out[cap + 10], 0xFF);
  EXPECT_EQ(out[cap + 11], 0x52);
}

}  // namespace
