// The public API (gpuj2k/encoder.h) as a program embedding the library uses it: buffers in every
// layout, every argument checked, the one error type, cancellation, concurrent encodes.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "gpuj2k/encoder.h"
#include "imageio/image.h"
#include "imageio/write.h"
#include "support/external_decode.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"

namespace {

using test_support::decode_with;
using test_support::ScratchDir;

// A generated image as interleaved 8- or 16-bit samples.
struct Buffer {
  imageio::Image image;
  std::vector<std::uint8_t> bytes8;
  std::vector<std::uint16_t> bytes16;
};

Buffer make_buffer(int w, int h, int channels, int bits) {
  Buffer b;
  b.image = testimages::generate(testimages::Pattern::Mix, w, h, channels, bits);
  for (float v : b.image.pixels) {
    if (bits <= 8)
      b.bytes8.push_back(static_cast<std::uint8_t>(v));
    else
      b.bytes16.push_back(static_cast<std::uint16_t>(v));
  }
  return b;
}

gpuj2k::ImageView view_of(const Buffer& b) {
  gpuj2k::ImageView v;
  v.width = b.image.width;
  v.height = b.image.height;
  v.components = b.image.channels;
  if (!b.bytes8.empty()) {
    v.data = b.bytes8.data();
    v.size_bytes = b.bytes8.size();
  } else {
    v.data = b.bytes16.data();
    v.size_bytes = 2 * b.bytes16.size();
    v.type = gpuj2k::SampleType::UInt16;
    v.bits = b.image.bits_per_sample;
  }
  return v;
}

std::string error_of(const gpuj2k::ImageView& v, const gpuj2k::EncodeOptions& o = {}) {
  try {
    gpuj2k::encode(v, o);
  } catch (const gpuj2k::Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Api, LosslessBufferDecodesToItselfInOpenJpeg) {
  ScratchDir scratch;
  for (const int bits : {8, 12}) {
    SCOPED_TRACE(bits);
    const Buffer b = make_buffer(67, 45, 3, bits);
    gpuj2k::EncodeOptions o;
    o.lossless = true;
    gpuj2k::EncodeReport report;
    const std::vector<std::uint8_t> j2k = gpuj2k::encode(view_of(b), o, &report);
    EXPECT_EQ(report.width, 67);
    EXPECT_EQ(report.components, 3);
    std::ofstream(scratch / "x.j2k", std::ios::binary)
        .write(reinterpret_cast<const char*>(j2k.data()), std::streamsize(j2k.size()));
    EXPECT_EQ(decode_with("opj_decompress", scratch / "x.j2k", scratch / "x.ppm").pixels, b.image.pixels);
  }
}

// The same samples in every layout the view describes give the same codestream.
TEST(Api, LayoutsAndStridesGiveTheSameStream) {
  const Buffer b = make_buffer(33, 21, 3, 8);
  gpuj2k::EncodeOptions o;
  o.rates_bpp = {4.0};
  const std::vector<std::uint8_t> expected = gpuj2k::encode(view_of(b), o);

  // Planar, with padded rows and padded planes.
  const std::size_t row = 40, plane = row * 21 + 13;
  std::vector<std::uint8_t> planar(plane * 3, 0xEE);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < 21; ++y)
      for (int x = 0; x < 33; ++x) planar[c * plane + y * row + x] = b.bytes8[(y * 33 + x) * 3 + c];
  gpuj2k::ImageView v = view_of(b);
  v.data = planar.data();
  v.size_bytes = planar.size();
  v.layout = gpuj2k::Layout::Planar;
  v.row_stride = row;
  v.plane_stride = plane;
  EXPECT_EQ(gpuj2k::encode(v, o), expected);

  // Interleaved in 32-bit integers with padded rows.
  std::vector<std::int32_t> wide(static_cast<std::size_t>(21) * 100, -7);
  for (int y = 0; y < 21; ++y)
    for (int i = 0; i < 33 * 3; ++i) wide[y * 100 + i] = b.bytes8[y * 33 * 3 + i];
  gpuj2k::ImageView w = view_of(b);
  w.data = wide.data();
  w.size_bytes = wide.size() * 4;
  w.type = gpuj2k::SampleType::Int32;
  w.bits = 8;
  w.row_stride = 400;
  EXPECT_EQ(gpuj2k::encode(w, o), expected);
}

TEST(Api, EveryBadArgumentIsTheOneErrorWithAClearMessage) {
  const Buffer b = make_buffer(16, 8, 3, 8);
  const gpuj2k::ImageView good = view_of(b);
  auto with = [&](auto change) {
    gpuj2k::ImageView v = good;
    change(v);
    return error_of(v);
  };
  EXPECT_NE(with([](auto& v) { v.size_bytes -= 1; }).find("smaller than the 384 bytes"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.data = nullptr; }).find("null"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.width = 0; }).find("empty"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.height = -3; }).find("empty or negative"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.components = 20000; }).find("outside 1..16384"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.bits = 9; }).find("outside 1..8"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.bits = 4; }).find("does not fit 4-bit"), std::string::npos);
  EXPECT_NE(with([](auto& v) { v.row_stride = 10; }).find("row stride 10"), std::string::npos);
  EXPECT_NE(with([](auto& v) {
              v.layout = gpuj2k::Layout::Planar;
              v.plane_stride = 100;
            }).find("plane stride 100"),
            std::string::npos);
  // Sizes whose byte counts overflow are refused before anything is read.
  EXPECT_NE(with([](auto& v) {
              v.width = v.height = 1 << 30;
              v.components = 16000;
              v.type = gpuj2k::SampleType::Int32;
              v.bits = 16;
            }).find("overflows"),
            std::string::npos);
  auto option_error = [&](auto change) {
    gpuj2k::EncodeOptions o;
    change(o);
    return error_of(good, o);
  };
  EXPECT_NE(option_error([](auto& o) { o.levels = 40; }).find("decomposition levels"), std::string::npos);
  EXPECT_NE(option_error([](auto& o) { o.codeblock_width = 3; }).find("code-block"), std::string::npos);
  EXPECT_NE(option_error([](auto& o) { o.rates_bpp = {-1}; }).find("rates must be positive"), std::string::npos);
  EXPECT_NE(option_error([](auto& o) {
              o.rates_bpp = {1};
              o.psnr_db = {30};
            }).find("one kind of target"),
            std::string::npos);
  EXPECT_NE(option_error([](auto& o) {
              o.lossless = true;
              o.rates_bpp = {1};
            }).find("lossless"),
            std::string::npos);
  // Library messages speak of parameters, never of command-line flags.
  EXPECT_EQ(option_error([](auto& o) { o.guard_bits = 9; }).find("--"), std::string::npos);
  try {
    gpuj2k::encode_file("/nonexistent/in.ppm", gpuj2k::EncodeOptions{});
    FAIL() << "no error";
  } catch (const gpuj2k::Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/in.ppm"), std::string::npos);
  }
}

TEST(Api, ProgressReportsAndCancels) {
  const Buffer b = make_buffer(300, 200, 3, 8);
  gpuj2k::EncodeOptions o;
  o.threads = 2;
  std::atomic<std::size_t> calls{0}, last_total{0};
  o.progress = [&](std::size_t, std::size_t total) {
    ++calls;
    last_total = total;
    return true;
  };
  gpuj2k::encode(view_of(b), o);
  EXPECT_GT(calls.load(), 0u);
  EXPECT_EQ(calls.load(), last_total.load());  // one call per code-block
  o.progress = [](std::size_t done, std::size_t) { return done < 3; };
  EXPECT_EQ(error_of(view_of(b), o), "encode cancelled");
}

// Encodes on several threads at once give the bytes of the same encodes one after the other.
TEST(Api, ConcurrentEncodesGiveTheSameBytes) {
  const Buffer a = make_buffer(120, 90, 3, 8), b = make_buffer(97, 64, 1, 16);
  gpuj2k::EncodeOptions lossy;
  lossy.rates_bpp = {0.5, 2.0};
  lossy.threads = 2;
  gpuj2k::EncodeOptions lossless;
  lossless.lossless = true;
  lossless.threads = 1;
  const std::vector<std::uint8_t> expected_a = gpuj2k::encode(view_of(a), lossy);
  const std::vector<std::uint8_t> expected_b = gpuj2k::encode(view_of(b), lossless);
  std::vector<std::vector<std::uint8_t>> got(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back(
        [&, i] { got[i] = i % 2 ? gpuj2k::encode(view_of(b), lossless) : gpuj2k::encode(view_of(a), lossy); });
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], i % 2 ? expected_b : expected_a) << i;
}

// Encodes sharing one engine (its worker threads) on several threads at once give the bytes of
// encodes with threads of their own.
TEST(Api, EncodesSharingAnEngineGiveTheSameBytes) {
  const Buffer a = make_buffer(120, 90, 3, 8), b = make_buffer(97, 64, 1, 16);
  auto engine = std::make_shared<gpuj2k::Engine>(2);
  EXPECT_EQ(engine->threads(), 2);
  gpuj2k::EncodeOptions lossy;
  lossy.rates_bpp = {0.5, 2.0};
  lossy.dwt = gpuj2k::DwtDevice::Cpu;
  gpuj2k::EncodeOptions lossless;
  lossless.lossless = true;
  const std::vector<std::uint8_t> expected_a = gpuj2k::encode(view_of(a), lossy);
  const std::vector<std::uint8_t> expected_b = gpuj2k::encode(view_of(b), lossless);
  lossy.engine = engine;
  lossless.engine = engine;
  std::vector<std::vector<std::uint8_t>> got(6);
  std::vector<gpuj2k::EncodeReport> reports(got.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] {
      got[i] =
          i % 2 ? gpuj2k::encode(view_of(b), lossless, &reports[i]) : gpuj2k::encode(view_of(a), lossy, &reports[i]);
    });
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i], i % 2 ? expected_b : expected_a) << i;
    EXPECT_EQ(reports[i].threads, 2) << i;
  }
}

// With the DWT on the GPU, encodes sharing an engine make one GL context between them (the first
// pays for it, the others find it ready) and, using it in turn from their own threads, give the
// bytes of an encode with a context of its own.
TEST(Api, EncodesSharingAnEngineShareOneGlContext) {
  const Buffer a = make_buffer(200, 150, 3, 8);
  gpuj2k::EncodeOptions options;
  options.rates_bpp = {1.0};
  options.dwt = gpuj2k::DwtDevice::Gpu;
  options.threads = 2;
  std::vector<std::uint8_t> expected;
  gpuj2k::EncodeReport alone;
  try {
    expected = gpuj2k::encode(view_of(a), options, &alone);
  } catch (const gpuj2k::Error& e) {
    GTEST_SKIP() << "no GL context on this machine: " << e.what();
  }
  options.engine = std::make_shared<gpuj2k::Engine>(2);
  std::vector<std::vector<std::uint8_t>> got(4);
  std::vector<gpuj2k::EncodeReport> reports(got.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] { got[i] = gpuj2k::encode(view_of(a), options, &reports[i]); });
  for (std::thread& t : threads) t.join();
  int made_contexts = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i], expected) << i;
    EXPECT_EQ(reports[i].dwt_backend, alone.dwt_backend) << i;
    made_contexts += reports[i].gl_context_ms > 0 ? 1 : 0;
  }
  EXPECT_EQ(made_contexts, 1);
  EXPECT_GT(alone.gl_context_ms, 0);
}

TEST(Api, VersionIsTheProjects) { EXPECT_EQ(gpuj2k::version(), GPUJ2K_EXPECTED_VERSION); }

}  // namespace
