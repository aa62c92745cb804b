// HTJ2K codestreams (j2kenc --ht, EncodeParams::ht), proven from outside: every stream is decoded
// by OpenJPEG (opj_decompress), Grok (grk_decompress) and OpenJPH (ojph_expand). Lossless streams
// must give back the input exactly across the option matrix Part 15 allows (sizes from 1x1, odd
// offsets and tiles, every code-block shape, progression orders with precincts, 8 and 16 bits,
// signed samples, 1 to 4 components). Lossy streams must decode to exactly the samples the EBCOT
// stream of the same quantisation decodes to in the same decoder (both code every bit of the same
// indices), at the PSNR such a decode gives.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "codec/encoder/encoder.h"
#include "codec/structure/error.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "psnr.h"
#include "support/external_decode.h"
#include "support/option_matrix.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"

namespace {

namespace fs = std::filesystem;
using Scratch = test_support::ScratchDir;
using test_support::decode_with;

const char* const kDecoders[] = {"opj_decompress", "grk_decompress", "ojph_expand"};

// ojph_expand writes PGM/PPM/TIFF; TIFF keeps 1 to 4 components and 16 bits.
fs::path output_for(const std::string& tool, const Scratch& s) {
  return s / (tool + (tool == "ojph_expand" ? ".tif" : ".png"));
}
std::string options_for(const std::string& tool) { return tool == "grk_decompress" ? "-H 1" : ""; }

imageio::Image generated(int w, int h, int channels, int bits, testimages::Pattern p = testimages::Pattern::Mix) {
  return testimages::generate(p, w, h, channels, bits, false, static_cast<std::uint64_t>(w * 131 + h));
}

codec::EncodeParams ht(bool lossless = true) {
  codec::EncodeParams p;
  p.lossless = lossless;
  p.ht = true;
  p.dwt = codec::DwtDevice::Cpu;
  p.threads = 2;
  return p;
}

// The stream must start with SOC, SIZ with Rsiz bit 14, then CAP with Pcap's Part 15 bit, and its
// COD must carry the HT code-block style bit.
void expect_ht_signalling(const std::vector<std::uint8_t>& cs) {
  ASSERT_GT(cs.size(), 60u);
  ASSERT_EQ(cs[2], 0xFF);
  ASSERT_EQ(cs[3], 0x51);
  EXPECT_EQ(cs[6] & 0x40, 0x40) << "Rsiz bit 14";
  const std::size_t cap = 4 + (static_cast<std::size_t>(cs[4]) << 8 | cs[5]);
  ASSERT_EQ(cs[cap], 0xFF);
  ASSERT_EQ(cs[cap + 1], 0x50) << "CAP right after SIZ";
  EXPECT_EQ(cs[cap + 4], 0x00);
  EXPECT_EQ(cs[cap + 5], 0x02) << "Pcap: Part 15";
  const std::size_t cod = cap + 2 + (static_cast<std::size_t>(cs[cap + 2]) << 8 | cs[cap + 3]);
  ASSERT_EQ(cs[cod + 1], 0x52);
  EXPECT_EQ(cs[cod + 12], 0x40) << "SPcod code-block style: HT";
}

std::size_t count_mismatches(const imageio::Image& a, const imageio::Image& b, std::size_t& first) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (a.pixels[i] != b.pixels[i] && n++ == 0) first = i;
  return n;
}

// Encodes losslessly with HT and requires every decoder to return the input. For tilings Grok
// 10.0.5 mis-decodes whatever the encoder (j2k_lossless_test.cpp), Grok's output must equal its
// output of OpenJPEG's EBCOT stream of the same tiling. OpenJPH 0.9 mis-decodes a few degenerate
// images (a 3x5 image on 5 levels) even from its own ojph_compress; where it fails on ours, it must
// fail on its own stream of the same image (`ojph_equivalent`: ojph_compress options) too.
void check_lossless(const std::string& name, const imageio::Image& image, const codec::EncodeParams& params,
                    const std::string& opj_equivalent = {}, const std::string& ojph_equivalent = {}) {
  SCOPED_TRACE(name);
  Scratch s;
  const auto bytes = codec::encode(codec::to_source_image(image, "generated"), params, codec::FileFormat::Codestream);
  expect_ht_signalling(bytes);
  const fs::path file = s / "x.j2k";
  test_support::write_bytes(file, bytes);
  for (const std::string tool : kDecoders) {
    if (!test_support::have_tool(tool)) {
      ADD_FAILURE() << tool << " is not installed (scripts/setup.sh installs it)";
      continue;
    }
    const imageio::Image back = decode_with(tool, file, output_for(tool, s), options_for(tool));
    ASSERT_EQ(back.width, image.width) << tool;
    ASSERT_EQ(back.height, image.height) << tool;
    ASSERT_EQ(back.channels, image.channels) << tool;
    std::size_t first = 0;
    const std::size_t bad = count_mismatches(back, image, first);
    if (bad != 0 && tool == "grk_decompress" && !opj_equivalent.empty()) {
      const fs::path source = s / (image.channels == 1 ? "in.pgm" : "in.ppm");
      imageio::write_image(source.string(), image);
      const std::string cmd = "opj_compress -i '" + source.string() + "' -o '" + (s / "opj.j2k").string() + "' " +
                              opj_equivalent + " >/dev/null 2>&1";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      const imageio::Image grok_of_opj = decode_with(tool, s / "opj.j2k", s / "grk_opj.png", "-H 1");
      EXPECT_EQ(back.pixels, grok_of_opj.pixels) << "Grok decodes our HT stream differently from OpenJPEG's EBCOT one";
      continue;
    }
    if (bad != 0 && tool == "ojph_expand" && !ojph_equivalent.empty()) {
      const fs::path source = s / (image.channels == 1 ? "in.pgm" : "in.ppm");
      imageio::write_image(source.string(), image);
      const std::string cmd = "ojph_compress -i '" + source.string() + "' -o '" + (s / "ojph.j2c").string() + "' " +
                              ojph_equivalent + " >/dev/null 2>&1";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
      const imageio::Image own = decode_with(tool, s / "ojph.j2c", s / "ojph_own.tif");
      std::size_t own_first = 0;
      EXPECT_NE(count_mismatches(own, image, own_first), 0u) << "OpenJPH decodes its own stream but not ours";
      std::printf("note: %s: ojph_expand mis-decodes ojph_compress's own stream of this image too\n", name.c_str());
      continue;
    }
    ASSERT_EQ(bad, 0u) << tool << ": first mismatch at sample " << first << ": " << back.pixels[first] << ", input "
                       << image.pixels[first];
  }
}

TEST(J2kHt, ComponentsAndDepths) {
  for (int channels : {1, 2, 3, 4})
    for (int bits : {8, 16})
      check_lossless(std::to_string(channels) + " components, " + std::to_string(bits) + " bits",
                     generated(61, 47, channels, bits), ht());
}

TEST(J2kHt, ThinAndTinyImages) {
  for (auto [w, h] : test_support::kThinAndTinySizes)
    for (int levels : {0, 1, 5}) {
      codec::EncodeParams p = ht();
      p.levels = levels;
      check_lossless(std::to_string(w) + "x" + std::to_string(h) + " levels " + std::to_string(levels),
                     generated(w, h, 1, 8), p, {}, "-num_decomps " + std::to_string(levels) + " -reversible true");
    }
}

TEST(J2kHt, TilesWithImageAndTileOffsets) {
  for (const test_support::Tiling& t : test_support::kTilings) {
    codec::EncodeParams p = ht();
    t.apply(p);
    check_lossless(t.name() + " RGB", generated(45, 38, 3, 8), p, t.opj_options());
  }
}

TEST(J2kHt, ProgressionOrdersWithPrecincts) {
  for (int order = 0; order < 5; ++order) {
    codec::EncodeParams p = ht();
    test_support::apply_order(p, order, true);
    p.sop = order % 2 == 0;
    p.eph = order % 2 == 1;
    check_lossless("order " + std::to_string(order), generated(70, 53, 3, 8), p);
  }
}

TEST(J2kHt, CodeBlockSizes) {
  for (auto [w, h] : test_support::kCodeBlockSizes) {
    codec::EncodeParams p = ht();
    p.codeblock_width = w;
    p.codeblock_height = h;
    check_lossless("code-blocks " + std::to_string(w) + "x" + std::to_string(h),
                   generated(150, 140, 1, 16, testimages::Pattern::Noise), p);
  }
}

// Signed samples: opj_decompress and grk_decompress write PGX, which both must match exactly.
// ojph_expand has no signed output: OpenJPH 0.9.0's raw/yuv writer (yuv_out::write in
// src/apps/others/ojph_img_io.cpp) clamps every sample to 0..2^B - 1, so our negative samples come
// out as 0. Its own signed streams seemed to keep theirs only because its raw reader (yuv_in::read)
// zero-extends the file's samples: nothing negative was ever coded. OpenJPH must match every
// non-negative sample and give 0 for the negative ones.
std::vector<std::int32_t> read_pgx(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string pg, ml, sign;
  int depth = 0, w = 0, h = 0;
  in >> pg >> ml >> std::ws;
  if (in.peek() == '+' || in.peek() == '-') in >> sign;
  in >> depth >> w >> h;
  in.get();
  const int bytes = depth <= 8 ? 1 : 2;
  std::vector<std::int32_t> out;
  for (int i = 0; i < w * h; ++i) {
    std::uint32_t v = 0;
    for (int b = 0; b < bytes; ++b) v = (v << 8) | static_cast<std::uint8_t>(in.get());
    auto s = static_cast<std::int32_t>(v);
    if (sign == "-" && (v >> (8 * bytes - 1)) & 1) s -= 1 << (8 * bytes);
    out.push_back(s);
  }
  return out;
}

std::vector<std::int32_t> read_raw(const fs::path& path, int bits) {
  std::ifstream in(path, std::ios::binary);
  const int bytes = bits <= 8 ? 1 : 2;
  std::vector<std::int32_t> out;
  for (;;) {  // 1-byte samples unsigned (nothing negative comes out), 2-byte ones sign-extended
    std::uint32_t v = 0;
    for (int b = 0; b < bytes; ++b) v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(in.get())) << (8 * b);
    if (!in) break;
    auto s = static_cast<std::int32_t>(v);
    if (bytes == 2 && (v >> 15) & 1) s -= 1 << 16;
    out.push_back(s);
  }
  return out;
}

TEST(J2kHt, SignedSamples) {
  for (int bits : {8, 12, 16}) {
    SCOPED_TRACE(bits);
    const imageio::Image img = testimages::generate(testimages::Pattern::Noise, 29, 19, 1, bits, true);
    Scratch s;
    const auto bytes = codec::encode(codec::to_source_image(img, "generated"), ht(), codec::FileFormat::Codestream);
    test_support::write_bytes(s / "s.j2k", bytes);
    for (const std::string tool : kDecoders) {
      const bool ojph = tool == "ojph_expand";

      const fs::path out = s / (tool + (ojph ? ".raw" : ".pgx"));
      ASSERT_EQ(std::system(
                    (tool + " -i '" + (s / "s.j2k").string() + "' -o '" + out.string() + "' >/dev/null 2>&1").c_str()),
                0)
          << tool;
      const auto decoded = ojph ? read_raw(out, bits) : read_pgx(s / (tool + "_0.pgx"));
      ASSERT_EQ(decoded.size(), img.pixels.size()) << tool;
      for (std::size_t i = 0; i < decoded.size(); ++i) {
        const auto expected = static_cast<std::int32_t>(img.pixels[i]);
        ASSERT_EQ(decoded[i], ojph ? std::max(expected, 0) : expected) << tool << " at " << i;
      }
    }
  }
}

// Lossy HT at a fixed step: the indices of an EBCOT encode that keeps every pass, except samples
// just under 1 in significant quads, which the HT encoder codes as 1 (ht_block_encoder.cpp, raising
// near-significant samples; HtBlock tests check the indices). Each decoder must decode it at least
// as close to the image as the EBCOT stream.
void check_lossy(const std::string& name, const imageio::Image& image, codec::EncodeParams params, double min_psnr) {
  SCOPED_TRACE(name);
  Scratch s;
  const auto source = codec::to_source_image(image, "generated");
  const auto ht_bytes = codec::encode(source, params, codec::FileFormat::Codestream);
  expect_ht_signalling(ht_bytes);
  EXPECT_EQ(ht_bytes[4 + (ht_bytes[4] << 8 | ht_bytes[5]) + 9] & 0x20, 0x20) << "Ccap15: irreversible";
  params.ht = false;
  const auto ebcot_bytes = codec::encode(source, params, codec::FileFormat::Codestream);
  test_support::write_bytes(s / "ht.j2k", ht_bytes);
  test_support::write_bytes(s / "ebcot.j2k", ebcot_bytes);
  for (const std::string tool : kDecoders) {
    const imageio::Image a = decode_with(tool, s / "ht.j2k", output_for(tool, s), options_for(tool));
    ASSERT_EQ(a.width, image.width) << tool;
    ASSERT_EQ(a.height, image.height) << tool;
    ASSERT_EQ(a.channels, image.channels) << tool;
    const double db = cli::psnr(image, a, image.bits_per_sample).all_db;
    EXPECT_GE(db, min_psnr) << tool;
    if (tool == "ojph_expand") continue;  // OpenJPH decodes only HT streams, not the EBCOT one
    const fs::path other = s / ("ebcot_" + output_for(tool, s).filename().string());
    const imageio::Image b = decode_with(tool, s / "ebcot.j2k", other, options_for(tool));
    EXPECT_GE(db, cli::psnr(image, b, image.bits_per_sample).all_db) << tool;
  }
}

TEST(J2kHt, LossyDecodesAtLeastAsWellAsTheEbcotStreamOfTheSameStep) {
  check_lossy("RGB 8 bits", generated(97, 75, 3, 8), ht(false), 45);
  check_lossy("grey 16 bits", generated(64, 80, 1, 16), ht(false), 45);
  codec::EncodeParams coarse = ht(false);
  coarse.base_step = 1.0 / 64;
  check_lossy("coarse steps", generated(97, 75, 3, 8), coarse, 28);
  codec::EncodeParams tiled = ht(false);
  test_support::kTilings[1].apply(tiled);
  check_lossy("tiled", generated(45, 38, 3, 8), tiled, 45);
  codec::EncodeParams blocks = ht(false);
  blocks.codeblock_width = 1024;
  blocks.codeblock_height = 4;
  check_lossy("1024x4 code-blocks", generated(120, 90, 1, 8), blocks, 45);
}

TEST(J2kHt, RefusesWhatItCannotDo) {
  const auto source = codec::to_source_image(generated(16, 16, 1, 8), "generated");
  codec::EncodeParams p = ht(false);
  p.layers = {codec::LayerTarget{codec::LayerTarget::Kind::Bytes, 300},
              codec::LayerTarget{codec::LayerTarget::Kind::Bytes, 500}};
  EXPECT_THROW(codec::encode(source, p, codec::FileFormat::Codestream), codec::EncodeError)
      << "one cleanup per block: one layer";
  codec::EncodeParams m = ht();
  m.block_style.bypass = true;
  EXPECT_THROW(codec::encode(source, m, codec::FileFormat::Codestream), codec::EncodeError);
}

}  // namespace
