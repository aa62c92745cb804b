// The public decoding API (gpuj2k/decoder.h) as a program uses it: library-allocated planes and
// caller buffers in every layout, the header read alone, windows, reductions and selections, every
// bad argument and a hostile stream as the one error type, and streams from OpenJPEG.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "gpuj2k/decoder.h"
#include "gpuj2k/encoder.h"
#include "support/deepened_stream.h"
#include "support/external_decode.h"
#include "support/jp2_boxes.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"

namespace {

using test_support::decode_with;
using test_support::ScratchDir;

// A generated image as interleaved samples in 16-bit words, and its lossless codestream.
struct Encoded {
  int width = 0, height = 0, components = 0, bits = 0;
  std::vector<std::uint16_t> samples;  // interleaved
  std::vector<std::uint8_t> j2k;
};

Encoded encode_lossless(int w, int h, int components, int bits, gpuj2k::Format format = gpuj2k::Format::Codestream) {
  Encoded e{w, h, components, bits, {}, {}};
  const imageio::Image image = testimages::generate(testimages::Pattern::Mix, w, h, components, bits);
  for (float v : image.pixels) e.samples.push_back(static_cast<std::uint16_t>(v));
  gpuj2k::ImageView view;
  view.data = e.samples.data();
  view.size_bytes = e.samples.size() * 2;
  view.width = w;
  view.height = h;
  view.components = components;
  view.type = gpuj2k::SampleType::UInt16;
  view.bits = bits;
  gpuj2k::EncodeOptions options;
  options.lossless = true;
  options.format = format;
  options.levels = 3;
  e.j2k = gpuj2k::encode(view, options);
  return e;
}

// An 8-bit RGB test image (the generator's mix pattern), and the view the encoder takes of it.
struct Rgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;
  gpuj2k::ImageView view() const {
    gpuj2k::ImageView v;
    v.data = pixels.data();
    v.size_bytes = pixels.size();
    v.width = width;
    v.height = height;
    v.components = 3;
    return v;
  }
};

Rgb8 rgb8_image(int w, int h) {
  Rgb8 out{w, h, {}};
  for (float v : testimages::generate(testimages::Pattern::Mix, w, h, 3, 8).pixels)
    out.pixels.push_back(static_cast<std::uint8_t>(v));
  return out;
}

std::string error_of(const std::vector<std::uint8_t>& bytes, const gpuj2k::OutputView& out,
                     const gpuj2k::DecodeOptions& options = {}) {
  try {
    gpuj2k::decode_into(bytes.data(), bytes.size(), out, options);
  } catch (const gpuj2k::Error& e) {
    return e.what();
  }
  return "no error";
}

// Samples of 38 bits (a lossless stream deepened by its markers, support/deepened_stream.h): decode
// gives them in wide_samples, read_info names their depth, and decode_into refuses every buffer
// type, none of which holds them.
TEST(ApiDecode, ThirtyEightBitSamplesComeAsInt64) {
  const Encoded e = encode_lossless(21, 13, 1, 8);
  const auto deep = test_support::deepened(e.j2k, 38, false, 7, 20);  // the coded planes 25 up
  EXPECT_EQ(gpuj2k::read_info(deep.data(), deep.size()).components.at(0).precision, 38);
  const gpuj2k::DecodedImage image = gpuj2k::decode(deep.data(), deep.size());
  ASSERT_EQ(image.components.size(), 1u);
  const gpuj2k::DecodedComponent& comp = image.components[0];
  EXPECT_EQ(comp.precision, 38);
  EXPECT_TRUE(comp.samples.empty());
  ASSERT_EQ(comp.wide_samples.size(), 21u * 13u);
  // Around 2^37 (the level shift) by 2^25 times the 8-bit stream's centred samples, give or take
  // the wavelet's rounding: far from 31 bits.
  const auto [low, high] = std::minmax_element(comp.wide_samples.begin(), comp.wide_samples.end());
  EXPECT_LT(*low, (std::int64_t{1} << 37) - (std::int64_t{1} << 31));
  EXPECT_GT(*high, (std::int64_t{1} << 37) + (std::int64_t{1} << 31));
  std::vector<std::int32_t> buffer(21 * 13);
  gpuj2k::OutputView out{buffer.data(), buffer.size() * 4, 21, 13, 1};
  out.type = gpuj2k::SampleType::Int32;
  EXPECT_NE(error_of(deep, out).find("38 bits"), std::string::npos) << error_of(deep, out);
}

TEST(ApiDecode, LosslessStreamsDecodeToTheirSamples) {
  for (const int bits : {8, 12, 16}) {
    for (const gpuj2k::Format format : {gpuj2k::Format::Codestream, gpuj2k::Format::Jp2}) {
      SCOPED_TRACE(bits);
      const Encoded e = encode_lossless(37, 23, 3, bits, format);
      const gpuj2k::DecodedImage image = gpuj2k::decode(e.j2k.data(), e.j2k.size());
      ASSERT_EQ(image.width(), 37);
      ASSERT_EQ(image.height(), 23);
      ASSERT_EQ(image.components.size(), 3u);
      for (int c = 0; c < 3; ++c) {
        const gpuj2k::DecodedComponent& comp = image.components[static_cast<std::size_t>(c)];
        EXPECT_EQ(comp.precision, bits);
        EXPECT_FALSE(comp.is_signed);
        for (std::size_t i = 0; i < comp.samples.size(); ++i)
          ASSERT_EQ(comp.samples[i], e.samples[i * 3 + static_cast<std::size_t>(c)])
              << "component " << c << " sample " << i;
      }
      EXPECT_TRUE(image.warnings.empty());
    }
  }
}

// decode_into writes the same samples in every layout and type that holds them, and never past
// the rows, pixels or planes the view describes.
TEST(ApiDecode, IntoCallerBuffersOfEveryLayout) {
  const Encoded e = encode_lossless(29, 17, 3, 8);
  const gpuj2k::ImageInfo info = gpuj2k::read_info(e.j2k.data(), e.j2k.size());
  ASSERT_EQ(info.width(), 29);
  ASSERT_EQ(info.height(), 17);
  ASSERT_EQ(info.components.size(), 3u);

  std::vector<std::uint8_t> tight(29 * 17 * 3);
  gpuj2k::OutputView out{tight.data(), tight.size(), 29, 17, 3};
  EXPECT_TRUE(gpuj2k::decode_into(e.j2k.data(), e.j2k.size(), out).empty());
  for (std::size_t i = 0; i < tight.size(); ++i) ASSERT_EQ(tight[i], e.samples[i]) << i;

  // Planar 16-bit words, rows padded to 40 samples, planes padded by 7 rows; the padding untouched.
  const std::size_t row = 40, plane = row * (17 + 7);
  std::vector<std::uint16_t> planar(plane * 3, 0xBEEF);
  gpuj2k::OutputView p{planar.data(),          planar.size() * 2, 29,       17, 3, gpuj2k::SampleType::UInt16,
                       gpuj2k::Layout::Planar, row * 2,           plane * 2};
  gpuj2k::decode_into(e.j2k.data(), e.j2k.size(), p);
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t y = 0; y < 24; ++y)
      for (std::size_t x = 0; x < row; ++x) {
        const std::uint16_t got = planar[c * plane + y * row + x];
        if (y < 17 && x < 29)
          ASSERT_EQ(got, e.samples[(y * 29 + x) * 3 + c]);
        else
          ASSERT_EQ(got, 0xBEEF) << "padding written at " << c << "," << y << "," << x;
      }

  // Interleaved 32-bit integers.
  std::vector<std::int32_t> wide(29 * 17 * 3);
  gpuj2k::OutputView w{wide.data(), wide.size() * 4, 29, 17, 3, gpuj2k::SampleType::Int32};
  gpuj2k::decode_into(e.j2k.data(), e.j2k.size(), w);
  for (std::size_t i = 0; i < wide.size(); ++i) ASSERT_EQ(wide[i], e.samples[i]);
}

// read_info tells from the headers what decode gives, with reduce, a region and a selection.
// A JP2 file's ICC profile reaches the caller, from read_info and from decode.
TEST(ApiDecode, IccProfileReachesTheCaller) {
  const Encoded e = encode_lossless(16, 8, 3, 8);
  const std::vector<std::uint8_t> profile = test_support::made_up_icc_profile(200);
  const auto file = test_support::jp2_file(
      e.j2k, {test_support::ihdr(16, 8, 3, 8), test_support::box("colr", test_support::icc_colr(profile))});
  EXPECT_EQ(gpuj2k::read_info(file.data(), file.size()).icc_profile, profile);
  EXPECT_EQ(gpuj2k::decode(file.data(), file.size()).icc_profile, profile);
  EXPECT_TRUE(gpuj2k::decode(e.j2k.data(), e.j2k.size()).icc_profile.empty());
}

// EncodeOptions' resolutions go into a JP2 file's resolution box, and read_info and decode give
// them back (within the box's 16-bit fractions), on the grid --reduce leaves; a resolution the
// box cannot hold is refused before coding.
TEST(ApiDecode, ResolutionRoundTrips) {
  const Rgb8 image = rgb8_image(16, 8);
  const gpuj2k::ImageView view = image.view();
  gpuj2k::EncodeOptions options;
  options.lossless = true;
  options.format = gpuj2k::Format::Jp2;
  options.levels = 2;
  options.capture_resolution = {3779.527559, 2834.645669};  // 96 and 72 dots per inch
  options.display_resolution = {10000, 10000};
  const std::vector<std::uint8_t> file = gpuj2k::encode(view, options);
  const gpuj2k::ImageInfo info = gpuj2k::read_info(file.data(), file.size());
  EXPECT_NEAR(info.capture_resolution.vertical, 3779.527559, 0.01);
  EXPECT_NEAR(info.capture_resolution.horizontal, 2834.645669, 0.01);
  EXPECT_DOUBLE_EQ(info.display_resolution.vertical, 10000);
  gpuj2k::DecodeOptions reduced;
  reduced.reduce = 1;
  const gpuj2k::DecodedImage half = gpuj2k::decode(file.data(), file.size(), reduced);
  EXPECT_NEAR(half.capture_resolution.vertical, 3779.527559 / 2, 0.01);
  EXPECT_DOUBLE_EQ(half.display_resolution.horizontal, 5000);
  options.format = gpuj2k::Format::Codestream;  // no box to put them in
  const std::vector<std::uint8_t> bare = gpuj2k::encode(view, options);
  EXPECT_FALSE(gpuj2k::read_info(bare.data(), bare.size()).capture_resolution.given());
  options.format = gpuj2k::Format::Jp2;
  options.capture_resolution = {-1, 72};
  EXPECT_THROW(gpuj2k::encode(view, options), gpuj2k::Error);
}

TEST(ApiDecode, InfoMatchesTheDecodeAndWindowsMatchTheWhole) {
  const Encoded e = encode_lossless(64, 48, 3, 8);
  const gpuj2k::DecodedImage whole = gpuj2k::decode(e.j2k.data(), e.j2k.size());
  gpuj2k::DecodeOptions o;
  o.region = gpuj2k::Region{10, 5, 31, 20};
  o.components = {2, 0};
  const gpuj2k::ImageInfo info = gpuj2k::read_info(e.j2k.data(), e.j2k.size(), o);
  const gpuj2k::DecodedImage part = gpuj2k::decode(e.j2k.data(), e.j2k.size(), o);
  ASSERT_EQ(part.components.size(), 2u);
  ASSERT_EQ(info.components.size(), 2u);
  EXPECT_EQ(info.width(), 31);
  EXPECT_EQ(info.height(), 20);
  for (std::size_t k = 0; k < 2; ++k) {
    const gpuj2k::DecodedComponent& got = part.components[k];
    EXPECT_EQ(info.components[k].width, got.width);
    EXPECT_EQ(info.components[k].height, got.height);
    const gpuj2k::DecodedComponent& all = whole.components[k == 0 ? 2 : 0];
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 31; ++x)
        ASSERT_EQ(got.samples[static_cast<std::size_t>(y * 31 + x)],
                  all.samples[static_cast<std::size_t>((y + 5) * 64 + x + 10)]);
  }
  gpuj2k::DecodeOptions reduced;
  reduced.reduce = 2;
  const gpuj2k::ImageInfo small = gpuj2k::read_info(e.j2k.data(), e.j2k.size(), reduced);
  EXPECT_EQ(small.width(), 16);
  EXPECT_EQ(small.height(), 12);
  EXPECT_EQ(gpuj2k::decode(e.j2k.data(), e.j2k.size(), reduced).components[0].samples.size(), 16u * 12u);
}

TEST(ApiDecode, EveryBadArgumentAndStreamIsTheOneErrorWithAClearMessage) {
  const Encoded e = encode_lossless(20, 10, 3, 12);
  std::vector<std::uint16_t> buffer(20 * 10 * 3);
  const gpuj2k::OutputView good{buffer.data(), buffer.size() * 2, 20, 10, 3, gpuj2k::SampleType::UInt16};
  EXPECT_EQ(error_of(e.j2k, good), "no error");
  gpuj2k::OutputView v = good;
  v.size_bytes -= 1;
  EXPECT_NE(error_of(e.j2k, v).find("output buffer of 1199 bytes is smaller than the 1200 bytes"), std::string::npos)
      << error_of(e.j2k, v);
  v = good;
  v.components = 1;
  EXPECT_NE(error_of(e.j2k, v).find("the image has 3 components, the output buffer 1"), std::string::npos);
  v = good;
  v.width = 10;
  EXPECT_NE(error_of(e.j2k, v).find("component 0 is 20x10 12-bit unsigned, the output buffer 10x10"), std::string::npos)
      << error_of(e.j2k, v);
  v = good;
  v.type = gpuj2k::SampleType::UInt8;
  EXPECT_NE(error_of(e.j2k, v).find("its samples do not fit uint8"), std::string::npos) << error_of(e.j2k, v);
  v = good;
  v.data = nullptr;
  EXPECT_EQ(error_of(e.j2k, v), "output data is null");
  gpuj2k::DecodeOptions o;
  o.reduce = 40;
  EXPECT_EQ(error_of(e.j2k, good, o), "reduce 40 is outside 0..32");
  o = {};
  o.components = {3};
  EXPECT_NE(error_of(e.j2k, good, o).find("component 3 asked for, but the image has 3"), std::string::npos);
  o = {};
  o.region = gpuj2k::Region{100, 100, 5, 5};
  EXPECT_NE(error_of(e.j2k, good, o).find("outside the image"), std::string::npos);
  o = {};
  o.max_memory = 1000;
  EXPECT_NE(error_of(e.j2k, good, o).find("over the memory limit"), std::string::npos);

  // Not JPEG 2000, cut short, and a missing file.
  const std::vector<std::uint8_t> text = {'h', 'e', 'l', 'l', 'o'};
  EXPECT_NE(error_of(text, good), "no error");
  const std::vector<std::uint8_t> cut(e.j2k.begin(), e.j2k.begin() + 40);
  EXPECT_NE(error_of(cut, good), "no error");
  try {
    gpuj2k::decode_file("/nonexistent/x.j2k");
    ADD_FAILURE() << "no error";
  } catch (const gpuj2k::Error& err) {
    EXPECT_EQ(std::string(err.what()), "/nonexistent/x.j2k: cannot open the file");
  }
}

// OpenJPEG's streams decode through the API as opj_decompress decodes them.
TEST(ApiDecode, OpenJpegStreamsDecodeAsOpenJpegDecodesThem) {
  ScratchDir scratch;
  const imageio::Image image = testimages::generate(testimages::Pattern::Mix, 45, 31, 3, 8);
  {
    std::ofstream ppm(scratch / "in.ppm", std::ios::binary);
    ppm << "P6\n45 31\n255\n";
    for (float v : image.pixels) ppm.put(static_cast<char>(static_cast<std::uint8_t>(v)));
  }
  const std::string cmd = "opj_compress -i '" + (scratch / "in.ppm").string() + "' -o '" +
                          (scratch / "x.j2k").string() + "' -r 20 -n 3 >/dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) GTEST_SKIP() << "opj_compress is not installed";
  const imageio::Image reference = decode_with("opj_decompress", scratch / "x.j2k", scratch / "x.ppm");
  const gpuj2k::DecodedImage ours = gpuj2k::decode_file((scratch / "x.j2k").string());
  ASSERT_EQ(ours.components.size(), 3u);
  int worst = 0;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < ours.components[c].samples.size(); ++i)
      worst = std::max(worst, std::abs(ours.components[c].samples[i] - static_cast<int>(reference.pixels[i * 3 + c])));
  EXPECT_LE(worst, 1);
}

TEST(ApiDecode, ConcurrentDecodesGiveTheSameSamples) {
  const Encoded e = encode_lossless(50, 40, 3, 8);
  const gpuj2k::DecodedImage expected = gpuj2k::decode(e.j2k.data(), e.j2k.size());
  std::vector<gpuj2k::DecodedImage> got(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] { got[i] = gpuj2k::decode(e.j2k.data(), e.j2k.size()); });
  for (std::thread& t : threads) t.join();
  for (const gpuj2k::DecodedImage& g : got)
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(g.components[c].samples, expected.components[c].samples);
}

// The report mirrors EncodeReport: where the inverse DWT ran and why, the threads, and stage times
// that are real (tier-1 and the DWT of a lossy stream take time; a CPU decode spends none on GL).
TEST(ApiDecode, ReportNamesTheDwtAndTimesTheStages) {
  const Rgb8 image = rgb8_image(96, 64);
  const gpuj2k::ImageView view = image.view();
  gpuj2k::EncodeOptions lossy;
  lossy.dwt = gpuj2k::DwtDevice::Cpu;
  lossy.rates_bpp = {1.0};
  const std::vector<std::uint8_t> j2k = gpuj2k::encode(view, lossy);
  gpuj2k::DecodeOptions options;
  options.threads = 2;
  gpuj2k::DecodeReport report;
  const gpuj2k::DecodedImage decoded = gpuj2k::decode(j2k.data(), j2k.size(), options, &report);
  EXPECT_EQ(report.threads, 2);
  EXPECT_EQ(report.dwt_backend.rfind("cpu lifting", 0), 0u) << report.dwt_backend;
  EXPECT_EQ(report.dwt_reason, "asked for the CPU");
  EXPECT_GT(report.tier1_ms, 0.0);
  EXPECT_GT(report.dwt_ms, 0.0);
  EXPECT_GT(report.component_transform_ms, 0.0);
  EXPECT_EQ(report.gl_context_ms + report.shader_compile_ms + report.upload_ms + report.download_ms, 0.0);
  EXPECT_EQ(report.read_ms, 0.0);  // from memory: nothing read

  // Auto never runs on a software renderer, and decodes the CPU's samples when it keeps the CPU.
  options.dwt = gpuj2k::DwtDevice::Auto;
  gpuj2k::DecodeReport automatic;
  const gpuj2k::DecodedImage again = gpuj2k::decode(j2k.data(), j2k.size(), options, &automatic);
  EXPECT_FALSE(automatic.dwt_reason.empty());
  if (automatic.dwt_backend.rfind("cpu", 0) == 0) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(again.components[c].samples, decoded.components[c].samples);
  } else {
    EXPECT_EQ(automatic.dwt_reason.rfind("the GPU is faster here", 0), 0u) << automatic.dwt_reason;
  }
}

}  // namespace
