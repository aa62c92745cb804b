// The decoder (codec/decoder) on HTJ2K codestreams: our encoder's HT streams over the lossless option
// matrix decode to exactly the input; OpenJPH's ojph_compress streams decode to exactly what
// ojph_expand makes of them (lossless: the input) or, lossy, within 1 of it (the 9/7 in float, in
// two implementations); Grok's HT streams (grk_compress -M 64) likewise against the input and
// opj_decompress; our lossy HT streams within 1 of opj_decompress. Corrupted HT streams give a
// DecodeError or an image, never a crash (CI runs this under ASan and UBSan too). Tests that need an
// outside tool skip with a message when it is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <iterator>
#include <string>
#include <vector>

#include "codec/decoder/decoder.h"
#include "codec/encoder/encoder.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "support/external_decode.h"
#include "support/option_matrix.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"
#include "testimages/prng.h"

namespace {

namespace fs = std::filesystem;
using test_support::have_tool;
using test_support::ScratchDir;
using testimages::Pattern;

imageio::Image image(Pattern p, int w, int h, int channels, int bits, bool is_signed = false) {
  return testimages::generate(p, w, h, channels, bits, is_signed);
}

codec::EncodeParams ht(bool lossless = true) {
  codec::EncodeParams p;
  p.lossless = lossless;
  p.ht = true;
  p.dwt = codec::DwtDevice::Cpu;
  p.threads = 1;
  return p;
}

std::vector<std::uint8_t> encode(const imageio::Image& img, const codec::EncodeParams& params,
                                 codec::FileFormat format = codec::FileFormat::Codestream) {
  return codec::encode(codec::to_source_image(img, "generated"), params, format);
}

codec::DecodedImage decode(const std::vector<std::uint8_t>& bytes) {
  codec::DecodeOptions o;
  o.threads = 1;
  return codec::decode(bytes, o);
}

// The largest difference between our decode and `theirs` (an image as imageio reads it, channels
// interleaved), or a failure when the shapes differ.
int max_difference(const codec::DecodedImage& ours, const imageio::Image& theirs, const std::string& what) {
  EXPECT_EQ(ours.components.size(), static_cast<std::size_t>(theirs.channels)) << what;
  if (ours.components.size() != static_cast<std::size_t>(theirs.channels)) return 1 << 30;
  int worst = 0;
  for (int c = 0; c < theirs.channels; ++c) {
    const codec::DecodedComponent& comp = ours.components[static_cast<std::size_t>(c)];
    EXPECT_EQ(comp.width, theirs.width) << what;
    EXPECT_EQ(comp.height, theirs.height) << what;
    if (comp.width != theirs.width || comp.height != theirs.height) return 1 << 30;
    for (int y = 0; y < theirs.height; ++y)
      for (int x = 0; x < theirs.width; ++x) {
        const auto want = static_cast<std::int64_t>(theirs.at(x, y, c));
        const std::int64_t got = comp.samples[static_cast<std::size_t>(y) * static_cast<std::size_t>(comp.width) +
                                              static_cast<std::size_t>(x)];
        worst = std::max(worst, static_cast<int>(std::min<std::int64_t>(std::abs(want - got), 1 << 30)));
      }
  }
  return worst;
}

void check_lossless(const imageio::Image& in, const codec::EncodeParams& params, const std::string& what) {
  SCOPED_TRACE(what);
  const auto stream = encode(in, params);
  const codec::DecodedImage out = decode(stream);
  EXPECT_TRUE(out.warnings.empty()) << what << ": " << (out.warnings.empty() ? "" : out.warnings[0]);
  EXPECT_EQ(max_difference(out, in, what), 0) << what;
  for (const codec::DecodedComponent& c : out.components) {
    EXPECT_EQ(c.precision, in.bits_per_sample) << what;
    EXPECT_EQ(c.is_signed, in.is_signed) << what;
  }
}

// ---- Our HT encoder's lossless option matrix: the input back ----

TEST(J2kHtDecode, OurLosslessImageKinds) {
  check_lossless(image(Pattern::Mix, 67, 45, 1, 8), ht(), "grey 8-bit");
  check_lossless(image(Pattern::Mix, 67, 45, 3, 8), ht(), "RGB 8-bit");
  check_lossless(image(Pattern::ZonePlate, 40, 33, 4, 8), ht(), "RGBA 8-bit");
  check_lossless(image(Pattern::Mix, 45, 38, 3, 16), ht(), "RGB 16-bit");
  for (int bits : {8, 12, 16})
    check_lossless(image(Pattern::Mix, 45, 38, 1, bits, true), ht(), "signed " + std::to_string(bits));
  check_lossless(image(Pattern::Noise, 31, 17, 1, 1), ht(), "1-bit");
  check_lossless(image(Pattern::Noise, 31, 17, 2, 5), ht(), "5-bit, 2 components");
  check_lossless(image(Pattern::Noise, 64, 64, 1, 16), ht(), "16-bit noise (large U-VLC residuals)");
}

TEST(J2kHtDecode, OurLosslessSizesTilingsOrdersCodeBlocks) {
  for (auto [w, h] : test_support::kThinAndTinySizes)
    check_lossless(image(Pattern::Mix, w, h, 1, 8), ht(), std::to_string(w) + "x" + std::to_string(h));
  for (int levels : {0, 1, 6}) {
    auto p = ht();
    p.levels = levels;
    check_lossless(image(Pattern::Edges, 70, 53, 3, 8), p, std::to_string(levels) + " levels");
  }
  const auto img = image(Pattern::Mix, 45, 38, 3, 8);
  for (const auto& t : test_support::kTilings) {
    auto p = ht();
    t.apply(p);
    check_lossless(img, p, t.name());
  }
  const auto img70 = image(Pattern::Mix, 70, 53, 3, 8);
  for (int order = 0; order < 5; ++order) {
    auto p = ht();
    test_support::apply_order(p, order, true);
    check_lossless(img70, p, "order " + std::to_string(order) + " with precincts");
  }
  const auto big = image(Pattern::Mix, 300, 140, 1, 8);
  for (auto [w, h] : test_support::kCodeBlockSizes) {
    auto p = ht();
    p.codeblock_width = w;
    p.codeblock_height = h;
    check_lossless(big, p, "code-blocks " + std::to_string(w) + "x" + std::to_string(h));
  }
  auto p = ht();
  p.sop = p.eph = true;
  check_lossless(img70, p, "SOP and EPH");
}

// ---- Outside encoders and decoders ----

// A Kodak-like photograph in miniature: the generated mix, written as PPM/PGM for the tools.
fs::path write_input(const ScratchDir& s, const imageio::Image& img) {
  const fs::path file = s / (img.channels == 1 ? "in.pgm" : "in.ppm");
  imageio::write_image(file.string(), img);
  return file;
}

std::vector<std::uint8_t> read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

TEST(J2kHtDecode, OpenJphStreamsDecodeAsOjphExpandDecodesThem) {
  if (!have_tool("ojph_compress") || !have_tool("ojph_expand"))
    GTEST_SKIP() << "ojph_compress/ojph_expand are not installed";
  struct Case {
    std::string options;
    bool lossless;
  };
  const Case cases[] = {
      {"-reversible true", true},
      {"-reversible true -num_decomps 2 -block_size {8,128} -prog_order LRCP", true},
      {"-reversible true -block_size {4,1024}", true},
      {"-reversible true -block_size {1024,4}", true},
      {"-reversible true -tile_size {50,40} -tile_offset {3,5} -image_offset {7,9} -precincts {32,32},{16,16}", true},
      {"-reversible true -prog_order CPRL -block_size {16,16} -precincts {64,64},{32,32},{16,16}", true},
      {"-qstep 0.01", false},
      {"-qstep 0.1 -num_decomps 3", false},
      {"-qstep 0.002 -block_size {32,32} -prog_order RLCP", false},
  };
  for (int channels : {1, 3}) {
    const auto img = image(Pattern::Mix, 173, 131, channels, 8);
    ScratchDir s;
    const fs::path input = write_input(s, img);
    for (const Case& c : cases) {
      const std::string what = std::to_string(channels) + " channel(s), ojph_compress " + c.options;
      SCOPED_TRACE(what);
      const fs::path stream = s / "ojph.j2c";
      ASSERT_TRUE(test_support::run_quietly("ojph_compress -i '" + input.string() + "' -o '" + stream.string() + "' " +
                                            c.options))
          << what;
      const imageio::Image theirs =
          test_support::decode_with("ojph_expand", stream, s / (channels == 1 ? "ref.pgm" : "ref.ppm"));
      const codec::DecodedImage ours = decode(read_file(stream));
      EXPECT_TRUE(ours.warnings.empty()) << what;
      EXPECT_LE(max_difference(ours, theirs, what), c.lossless ? 0 : 1) << what;
      if (c.lossless) {
        EXPECT_EQ(max_difference(ours, img, what), 0) << what;
      }
    }
  }
}

TEST(J2kHtDecode, OpenJph16BitStreams) {
  if (!have_tool("ojph_compress") || !have_tool("ojph_expand"))
    GTEST_SKIP() << "ojph_compress/ojph_expand are not installed";
  const auto img = image(Pattern::Mix, 97, 61, 1, 16);
  ScratchDir s;
  const fs::path input = write_input(s, img);
  const fs::path stream = s / "ojph16.j2c";
  ASSERT_TRUE(test_support::run_quietly("ojph_compress -i '" + input.string() + "' -o '" + stream.string() +
                                        "' -reversible true"));
  const codec::DecodedImage ours = decode(read_file(stream));
  EXPECT_EQ(max_difference(ours, img, "16-bit"), 0);
  EXPECT_EQ(max_difference(ours, test_support::decode_with("ojph_expand", stream, s / "ref16.pgm"), "16-bit"), 0);
}

TEST(J2kHtDecode, GrokHtStreams) {
  if (!have_tool("grk_compress") || !have_tool("opj_decompress"))
    GTEST_SKIP() << "grk_compress/opj_decompress are not installed";
  const auto img = image(Pattern::Mix, 173, 131, 3, 8);
  ScratchDir s;
  const fs::path input = write_input(s, img);
  struct Case {
    std::string options;
    bool lossless;
  };
  const Case cases[] = {{"-M 64", true},
                        {"-M 64 -b 32,32 -p RPCL -c [64,64],[32,32]", true},
                        {"-M 64 -I -r 20", false},
                        {"-M 64 -I -q 40", false}};
  for (const Case& c : cases) {
    const std::string what = "grk_compress " + c.options;
    SCOPED_TRACE(what);
    const fs::path stream = s / "grk.j2k";
    ASSERT_TRUE(
        test_support::run_quietly("grk_compress -i '" + input.string() + "' -o '" + stream.string() + "' " + c.options))
        << what;
    const codec::DecodedImage ours = decode(read_file(stream));
    EXPECT_TRUE(ours.warnings.empty()) << what;
    if (c.lossless) {
      EXPECT_EQ(max_difference(ours, img, what), 0) << what;
    }
    EXPECT_LE(max_difference(ours, test_support::decode_with("opj_decompress", stream, s / "opj.png"), what),
              c.lossless ? 0 : 1)
        << what;
  }
}

TEST(J2kHtDecode, OurLossyStreamsDecodeLikeOpjDecompress) {
  if (!have_tool("opj_decompress")) GTEST_SKIP() << "opj_decompress is not installed";
  const auto img = image(Pattern::Mix, 150, 101, 3, 8);
  ScratchDir s;
  std::vector<std::pair<std::string, codec::EncodeParams>> cases;
  cases.emplace_back("default steps", ht(false));
  auto sized = ht(false);
  sized.layers = {{codec::LayerTarget::Kind::Bytes, 6000}};
  cases.emplace_back("6000 bytes", sized);
  auto tiled = ht(false);
  tiled.tile_width = 64;
  tiled.tile_height = 48;
  tiled.codeblock_width = 16;
  tiled.codeblock_height = 64;
  tiled.order = codec::Progression::PCRL;
  tiled.precincts = {{32, 32}, {16, 16}};
  cases.emplace_back("tiles, precincts, PCRL", tiled);
  for (const auto& [what, params] : cases) {
    SCOPED_TRACE(what);
    const auto stream = encode(img, params);
    test_support::write_bytes(s / "ours.j2k", stream);
    const codec::DecodedImage ours = decode(stream);
    EXPECT_TRUE(ours.warnings.empty()) << what;
    EXPECT_LE(max_difference(ours, test_support::decode_with("opj_decompress", s / "ours.j2k", s / "opj.png"), what), 1)
        << what;
  }
}

// ---- JPH files (T.814 Annex D) ----

// The file type box of a JPH file: brand 'jph ', minor version 0, 'jph ' in the compatibility list;
// then the JP2 header superbox and the codestream box, as in JP2.
void expect_jph_boxes(const std::vector<std::uint8_t>& f) {
  ASSERT_GT(f.size(), 40u);
  const std::vector<std::uint8_t> signature_and_ftyp{0,    0,   0, 0x0C, 'j',  'P', ' ', ' ', 0x0D, 0x0A, 0x87,
                                                     0x0A, 0,   0, 0,    0x14, 'f', 't', 'y', 'p',  'j',  'p',
                                                     'h',  ' ', 0, 0,    0,    0,   'j', 'p', 'h',  ' '};
  EXPECT_EQ(std::vector<std::uint8_t>(f.begin(), f.begin() + 32), signature_and_ftyp);
  EXPECT_EQ(std::string(f.begin() + 36, f.begin() + 40), "jp2h");
}

TEST(J2kHtDecode, JphFilesDecodeInEveryDecoder) {
  struct Case {
    std::string what;
    imageio::Image image;
  };
  const Case cases[] = {{"RGB 8-bit", image(Pattern::Mix, 83, 61, 3, 8)},
                        {"grey 16-bit", image(Pattern::Mix, 61, 83, 1, 16)},
                        {"RGBA 8-bit", image(Pattern::ZonePlate, 40, 33, 4, 8)}};
  ScratchDir s;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto file = encode(c.image, ht(), codec::FileFormat::Jph);
    expect_jph_boxes(file);
    EXPECT_EQ(max_difference(decode(file), c.image, c.what), 0);
    const fs::path jph = s / "x.jph";
    test_support::write_bytes(jph, file);
    for (const std::string tool : {"opj_decompress", "grk_decompress", "ojph_expand"}) {
      if (!have_tool(tool)) {
        std::cout << "[ SKIPPED  ] " << tool << " is not installed\n";
        continue;
      }
      // ojph_expand writes PNM only for 1 or 3 components; TIFF keeps 4 and 16 bits.
      const fs::path out = s / (tool + (tool == "ojph_expand" ? ".tif" : ".png"));
      const imageio::Image theirs = test_support::decode_with(tool, jph, out, tool == "grk_decompress" ? "-H 1" : "");
      EXPECT_EQ(max_difference(decode(file), theirs, c.what + " vs " + tool), 0) << tool;
    }
  }
}

TEST(J2kHtDecode, JphWithoutHtIsRefused) {
  auto p = ht();
  p.ht = false;
  EXPECT_THROW(encode(image(Pattern::Mix, 16, 16, 1, 8), p, codec::FileFormat::Jph), std::invalid_argument);
}

// ---- Robustness ----

void decode_or_refuse(const std::vector<std::uint8_t>& bytes) {
  try {
    (void)decode(bytes);
  } catch (const codec::DecodeError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(J2kHtDecode, TruncatedAndCorruptedHtStreamsNeverCrash) {
  const auto img = image(Pattern::Mix, 37, 29, 3, 8);
  auto p = ht();
  p.codeblock_width = p.codeblock_height = 8;
  p.precincts = {{16, 16}, {8, 8}};
  const auto lossless_stream = encode(img, p);
  const auto lossy_stream = encode(img, ht(false));
  int run = 0;
  for (const auto& stream : {lossless_stream, lossy_stream}) {
    for (std::size_t len = 0; len < stream.size(); len += (len < 200 ? 3 : 11))
      decode_or_refuse(std::vector<std::uint8_t>(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(len)));
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<std::uint8_t> bytes = stream;
      for (int f = 0; f < 1 + trial % 4; ++f) {
        const std::uint64_t r =
            testimages::splitmix64_at(static_cast<std::uint64_t>(run), static_cast<std::uint64_t>(f));
        // Half the trials hit the packet data, where the HT segments are.
        const std::size_t from = (trial % 2) ? std::min<std::size_t>(bytes.size() - 1, 150) : 0;
        bytes[from + static_cast<std::size_t>(r % (bytes.size() - from))] ^=
            static_cast<std::uint8_t>(1u << ((r >> 32) % 8));
      }
      ++run;
      SCOPED_TRACE("trial " + std::to_string(trial));
      decode_or_refuse(bytes);
    }
  }
}

}  // namespace
