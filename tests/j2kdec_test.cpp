// j2kdec from the outside: --timing's stage table and JSON, --dwt auto's choice and its reason,
// and the summary line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "codec/encoder/encoder.h"
#include "glcontext/context.h"
#include "imageio/read.h"
#include "codec/decoder/decoder.h"
#include "support/deepened_stream.h"
#include "support/external_decode.h"
#include "support/jp2_boxes.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"

namespace {

namespace fs = std::filesystem;

struct ProcessResult {
  int exit_code = 0;
  std::string err;
};

ProcessResult run(const std::string& command, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const int status = std::system((command + " 2>'" + err.string() + "' >/dev/null").c_str());
  ProcessResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  std::ifstream in(err);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  return r;
}

// Runs j2kdec with `args`, capturing stderr.
ProcessResult j2kdec(const std::string& args, const fs::path& dir) {
  return run(std::string("'") + J2KDEC_PATH + "' " + args, dir);
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The decoder's stages in data-flow order, as --timing names them.
const std::vector<std::string> kStages = {"input read",
                                          "header parse",
                                          "setup",
                                          "GL context creation",
                                          "shader compilation",
                                          "tier-2",
                                          "tier-1 + dequantization",
                                          "upload",
                                          "inverse DWT compute",
                                          "download",
                                          "inverse MCT + DC shift",
                                          "output"};

class J2kdecCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // --dwt auto's calibration cache, kept out of the user's home.
    ::setenv("GPUJ2K_CACHE_DIR", scratch.path().c_str(), 1);
    stream = scratch / "mix.j2k";
    const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 320, 240, 3, 8);
    codec::EncodeParams p;
    p.lossless = false;
    p.dwt = codec::DwtDevice::Cpu;
    p.layers.push_back({codec::LayerTarget::Kind::Bytes, 320 * 240 * 1.0 / 8});
    const auto bytes = codec::encode(codec::to_source_image(img, "mix"), p, codec::FileFormat::Codestream);
    std::ofstream(stream, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  void TearDown() override { ::unsetenv("GPUJ2K_CACHE_DIR"); }

  std::string decode_args(const std::string& output, const std::string& more) const {
    return "-i '" + stream.string() + "' -o '" + (scratch / output).string() + "' " + more;
  }

  test_support::ScratchDir scratch{"j2kdec_test"};
  fs::path stream;
};

// The number after `name` at the start of a table row ("  name   12.34"), or NaN when absent.
double row_value(const std::string& table, const std::string& name) {
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  " + name + " ", 0) != 0) continue;
    return std::stod(line.substr(2 + name.size()));
  }
  return std::nan("");
}

TEST_F(J2kdecCli, TimingTableHasEveryStageAndTheyAddUpToTheSumLine) {
  const auto r = j2kdec(decode_args("t.ppm", "--dwt cpu --timing"), scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("j2kdec: timing in ms, DWT on cpu", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("(asked for the CPU)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" threads\n"), std::string::npos) << r.err;
  double sum = 0;
  for (const std::string& stage : kStages) {
    const double ms = row_value(r.err, stage);
    ASSERT_FALSE(std::isnan(ms)) << stage << " missing from\n" << r.err;
    EXPECT_GE(ms, 0.0) << stage;
    sum += ms;
  }
  EXPECT_GT(row_value(r.err, "tier-1 + dequantization"), 0.0);
  EXPECT_GT(row_value(r.err, "inverse DWT compute"), 0.0);
  // Each printed cell is rounded to 0.01 ms: the printed sum may differ by half of that per stage.
  const double sum_line = row_value(r.err, "sum of stages"), total = row_value(r.err, "total (measured)");
  EXPECT_NEAR(sum, sum_line, 0.005 * static_cast<double>(kStages.size()) + 0.005);
  // Nothing of the run is left out of the stages but option handling and the worker threads' end:
  // a stage missing from the sum (tier-1 or the DWT is a third of this decode or more) shows. The
  // margin is wide because other processes on a 2-core CI machine delay those threads' ends.
  EXPECT_LE(sum_line, total + 0.01);
  EXPECT_NEAR(sum_line, total, std::max(0.2 * total, 5.0)) << r.err;
}

TEST_F(J2kdecCli, TimingJsonIsValidWithTheSameStages) {
  if (std::system("/usr/bin/python3 -c 'import json' >/dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  const auto r = j2kdec(decode_args("t.pgx", "--dwt cpu --timing=json"), scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path json = scratch / "timing.json", names = scratch / "stages.txt";
  std::ofstream(json) << r.err;
  {
    std::ofstream out(names);
    for (const std::string& stage : kStages) out << stage << '\n';
  }
  // Python's parser is the judge of validity; it also checks the keys, their order and the sum.
  const std::string check =
      "import json, sys\n"
      "d = json.load(open(sys.argv[1]))\n"
      "want = open(sys.argv[2]).read().splitlines()\n"
      "assert list(d['stages_ms']) == want, list(d['stages_ms'])\n"
      "assert all(isinstance(v, float) and v >= 0 for v in d['stages_ms'].values())\n"
      "assert abs(sum(d['stages_ms'].values()) - d['sum_ms']) < 1e-3, d\n"
      "assert d['sum_ms'] <= d['total_ms'] + 1e-3, d\n"
      "assert d['dwt'].startswith('cpu') and d['dwt_reason'] == 'asked for the CPU' and d['threads'] >= 1, d\n";
  std::ofstream(scratch / "check.py") << check;
  const auto c =
      run("/usr/bin/python3 '" + (scratch / "check.py").string() + "' '" + json.string() + "' '" + names.string() + "'",
          scratch.path());
  EXPECT_EQ(c.exit_code, 0) << c.err << "\nfrom: " << r.err;
}

// Without a hardware GPU (CI: llvmpipe at most), auto picks the CPU, says why, and decodes what
// --dwt cpu decodes. With one, it may pick the GPU, but never a software renderer.
TEST_F(J2kdecCli, DwtAutoNeverPicksASoftwareRendererAndSaysWhy) {
  const auto cpu = j2kdec(decode_args("cpu.ppm", "--dwt cpu"), scratch.path());
  ASSERT_EQ(cpu.exit_code, 0) << cpu.err;
  const auto automatic = j2kdec(decode_args("auto.ppm", "--dwt auto -v"), scratch.path());
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  std::printf("%s", automatic.err.c_str());
  const auto on = automatic.err.find(", DWT on ");
  ASSERT_NE(on, std::string::npos) << automatic.err;
  const std::string backend = automatic.err.substr(on + 9);
  if (backend.rfind("gpu fragment shaders (", 0) == 0)
    EXPECT_FALSE(glc::is_software_renderer(backend.substr(0, backend.find(") ("))));
  else
    EXPECT_EQ(backend.rfind("cpu lifting", 0), 0u) << backend;
  bool hardware = false;
  try {
    hardware = glc::Context::create_hardware() != nullptr;
  } catch (const std::exception&) {
  }
  if (!hardware) {
    EXPECT_EQ(backend.rfind("cpu lifting", 0), 0u) << backend;
    EXPECT_NE(backend.find("no hardware GPU"), std::string::npos) << backend;
    EXPECT_NE(backend.find("the 9/7 runs on the CPU"), std::string::npos) << backend;
  }
  if (backend.rfind("cpu", 0) == 0) {
    EXPECT_EQ(file_bytes(scratch / "auto.ppm"), file_bytes(scratch / "cpu.ppm"));
  }
}

// --dwt gpu takes any GL context, llvmpipe included, and --timing splits the GPU's stages.
TEST_F(J2kdecCli, DwtGpuRunsOnAnyContextAndSplitsItsStages) {
  const auto r = j2kdec(decode_args("gpu.ppm", "--dwt gpu --timing"), scratch.path());
  if (r.exit_code != 0 && r.err.find("no GL context could be made") != std::string::npos)
    GTEST_SKIP() << "no GL context: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("j2kdec: timing in ms, DWT on gpu fragment shaders (", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("(asked for the GPU)"), std::string::npos) << r.err;
  EXPECT_GT(row_value(r.err, "GL context creation"), 0.0) << r.err;
  EXPECT_GT(row_value(r.err, "inverse DWT compute"), 0.0) << r.err;
  EXPECT_GT(row_value(r.err, "download"), 0.0) << r.err;
}

// A lossless stream needs no GL context: the reason says so whatever --dwt asks.
TEST_F(J2kdecCli, ReversibleStreamsKeepTheDwtOnTheCpu) {
  const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 64, 48, 1, 8);
  codec::EncodeParams p;
  p.lossless = true;
  const auto bytes = codec::encode(codec::to_source_image(img, "mix"), p, codec::FileFormat::Codestream);
  std::ofstream(stream, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto r = j2kdec(decode_args("l.pgm", "--dwt gpu -v"), scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("DWT on cpu lifting"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no irreversible tile-component"), std::string::npos) << r.err;
}

TEST_F(J2kdecCli, BadTimingModeIsOneLine) {
  const auto r = j2kdec(decode_args("x.ppm", "--timing=yaml"), scratch.path());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--timing takes text or json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch / "x.ppm"));
}

}  // namespace

namespace {

// A JP2 file of the fixture's image with a restricted ICC colr box holding `profile`.
fs::path jp2_with_profile(const fs::path& stream, const std::vector<std::uint8_t>& profile, const fs::path& file) {
  const std::string codestream = file_bytes(stream);
  const auto bytes = test_support::jp2_file(
      std::vector<std::uint8_t>(codestream.begin(), codestream.end()),
      {test_support::ihdr(320, 240, 3, 8), test_support::box("colr", test_support::icc_colr(profile))});
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return file;
}

}  // namespace

// A JP2 file's ICC profile ends up in TIFF and PNG outputs; PNM and PGX cannot carry it, and the
// user is told; a profile the PNG writer refuses leaves the image written without it, and says so.
TEST_F(J2kdecCli, IccProfileIsHandedToTheOutput) {
  const std::vector<std::uint8_t> profile = test_support::made_up_icc_profile(400);
  const fs::path jp2 = jp2_with_profile(stream, profile, scratch / "icc.jp2");
  const imageio::Image plain = [&] {
    EXPECT_EQ(
        j2kdec("-i '" + stream.string() + "' -o '" + (scratch / "plain.tif").string() + "'", scratch.path()).exit_code,
        0);
    return imageio::read_image((scratch / "plain.tif").string());
  }();
  for (const std::string name : {"icc.tif", "icc.png"}) {
    const auto r = j2kdec("-i '" + jp2.string() + "' -o '" + (scratch / name).string() + "'", scratch.path());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_EQ(r.err, "") << name;
    const imageio::Image out = imageio::read_image((scratch / name).string());
    EXPECT_EQ(out.icc_profile, profile) << name;
    EXPECT_EQ(out.pixels, plain.pixels) << name;  // the samples as they are: no colour conversion
  }
  for (const std::string name : {"icc.ppm", "icc.pgx"}) {
    const auto r = j2kdec("-i '" + jp2.string() + "' -o '" + (scratch / name).string() + "'", scratch.path());
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_NE(r.err.find("ICC colour profile (400 bytes) is not written"), std::string::npos) << name << ": " << r.err;
  }
  std::vector<std::uint8_t> not_d50 = profile;
  std::fill(not_d50.begin() + 68, not_d50.begin() + 80, std::uint8_t{0});  // libpng checks the PCS illuminant
  const fs::path refused = jp2_with_profile(stream, not_d50, scratch / "refused.jp2");
  const auto r =
      j2kdec("-i '" + refused.string() + "' -o '" + (scratch / "refused.png").string() + "'", scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("refused by the writer"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const imageio::Image written = imageio::read_image((scratch / "refused.png").string());
  EXPECT_TRUE(written.icc_profile.empty());
  EXPECT_EQ(written.pixels, plain.pixels);
}

namespace {

// A JP2 file of a 64x48 test image with the given resolutions.
fs::path jp2_with_resolution(const codec::GridResolution& capture, const codec::GridResolution& display,
                             const fs::path& file) {
  codec::EncodeParams p;
  p.dwt = codec::DwtDevice::Cpu;
  p.capture_resolution = capture;
  p.display_resolution = display;
  const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 64, 48, 3, 8);
  const auto bytes = codec::encode(codec::to_source_image(img, "mix"), p, codec::FileFormat::Jp2);
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return file;
}

}  // namespace

// A JP2 file's resolution reaches TIFF, PNG and JPEG outputs in pixels per metre (the display
// resolution where the file has one, else the capture resolution), on the grid --reduce leaves;
// j2kenc carries an input file's resolution into the JP2 file it writes; and the boxes are Grok's:
// grk_decompress reads ours, and we read what grk_compress -Q writes.
TEST_F(J2kdecCli, ResolutionReachesTheOutput) {
  const fs::path capture_only = jp2_with_resolution({2000, 3780}, {}, scratch / "capture.jp2");
  auto decoded = [&](const fs::path& in, const std::string& name, const std::string& more = "") {
    const auto r = j2kdec("-i '" + in.string() + "' -o '" + (scratch / name).string() + "' " + more, scratch.path());
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    return imageio::read_image((scratch / name).string());
  };
  for (const auto& [name, tolerance] :
       {std::pair<std::string, double>{"res.tif", 0.05}, {"res.png", 1.0}, {"res.jpg", 100.0}}) {
    const imageio::Image out = decoded(capture_only, name);
    EXPECT_NEAR(out.x_pixels_per_metre, 3780, tolerance) << name;
    EXPECT_NEAR(out.y_pixels_per_metre, 2000, tolerance) << name;
  }
  const imageio::Image half = decoded(capture_only, "half.png", "--reduce 1");
  EXPECT_NEAR(half.x_pixels_per_metre, 1890, 1.0);
  EXPECT_NEAR(half.y_pixels_per_metre, 1000, 1.0);
  const imageio::Image display =
      decoded(jp2_with_resolution({2000, 3780}, {7200, 5000}, scratch / "display.jp2"), "display.png");
  EXPECT_NEAR(display.x_pixels_per_metre, 5000, 1.0);
  EXPECT_NEAR(display.y_pixels_per_metre, 7200, 1.0);
  EXPECT_EQ(decoded(stream, "none.png").x_pixels_per_metre, 0);  // a codestream has none

  // j2kenc: the PNG's resolution into the JP2 file, and back out.
  const std::string encode = std::string("'") + J2KENC_PATH + "' -q -i '" + (scratch / "res.png").string() + "' -o '" +
                             (scratch / "again.jp2").string() + "' --lossless";
  ASSERT_EQ(run(encode, scratch.path()).exit_code, 0);
  const imageio::Image again = decoded(scratch / "again.jp2", "again.png");
  EXPECT_NEAR(again.x_pixels_per_metre, 3780, 1.0);
  EXPECT_NEAR(again.y_pixels_per_metre, 2000, 1.0);
  // Or as asked on the command line, X,Y as grk_compress -D takes them; a malformed pair is refused.
  ASSERT_EQ(run(encode + " --display-resolution 5000,7200", scratch.path()).exit_code, 0);
  const imageio::Image asked = decoded(scratch / "again.jp2", "asked.png");
  EXPECT_NEAR(asked.x_pixels_per_metre, 5000, 1.0);
  EXPECT_NEAR(asked.y_pixels_per_metre, 7200, 1.0);
  const ProcessResult bad = run(encode + " --capture-resolution 72", scratch.path());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--capture-resolution takes X,Y in pixels per metre"), std::string::npos) << bad.err;

  if (!test_support::have_tool("grk_decompress") || !test_support::have_tool("grk_compress"))
    GTEST_SKIP() << "grk_decompress or grk_compress not installed: the cross-check with Grok was not run";
  const imageio::Image by_grok = test_support::decode_with("grk_decompress", capture_only, scratch / "grok.tif");
  EXPECT_NEAR(by_grok.x_pixels_per_metre, 3780, 0.05);
  EXPECT_NEAR(by_grok.y_pixels_per_metre, 2000, 0.05);
  const std::string grok_encode = "grk_compress -i '" + (scratch / "res.png").string() + "' -o '" +
                                  (scratch / "grok.jp2").string() + "' -Q 3780,2000 >/dev/null";
  ASSERT_EQ(run(grok_encode, scratch.path()).exit_code, 0);
  const imageio::Image from_grok = decoded(scratch / "grok.jp2", "from_grok.png");
  EXPECT_NEAR(from_grok.x_pixels_per_metre, 3780, 1.0);
  EXPECT_NEAR(from_grok.y_pixels_per_metre, 2000, 1.0);
}

// A 38-bit stream (support/deepened_stream.h) goes to PGX with 8-byte samples, the library's
// decode exactly; formats that cannot hold 38 bits refuse it in one line, and write nothing.
TEST_F(J2kdecCli, ThirtyEightBitSamplesGoToPgxAndNowhereElse) {
  const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 37, 29, 1, 8);
  codec::EncodeParams p;
  p.lossless = true;
  p.threads = 1;
  const auto deep = test_support::deepened(
      codec::encode(codec::to_source_image(img, "mix"), p, codec::FileFormat::Codestream), 38, false, 7, 20);
  const fs::path input = scratch / "deep.j2k";
  std::ofstream(input, std::ios::binary)
      .write(reinterpret_cast<const char*>(deep.data()), static_cast<std::streamsize>(deep.size()));
  const codec::DecodedImage want = codec::decode(deep);
  ASSERT_EQ(want.components.size(), 1u);
  ASSERT_EQ(want.components[0].wide_samples.size(), 37u * 29u);

  const auto r = j2kdec("-i '" + input.string() + "' -o '" + (scratch / "deep.pgx").string() + "'", scratch.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string pgx = file_bytes(scratch / "deep_0.pgx");
  const std::string header = "PG ML + 38 37 29\n";
  ASSERT_EQ(pgx.substr(0, header.size()), header);
  ASSERT_EQ(pgx.size(), header.size() + 37u * 29u * 8u);
  for (std::size_t i = 0; i < want.components[0].wide_samples.size(); ++i) {
    std::uint64_t v = 0;
    for (std::size_t b = 0; b < 8; ++b) v = v << 8 | static_cast<unsigned char>(pgx[header.size() + 8 * i + b]);
    ASSERT_EQ(static_cast<std::int64_t>(v), want.components[0].wide_samples[i]) << "sample " << i;
  }
  for (const std::string name : {"deep.png", "deep.tif", "deep.pgm"}) {
    const auto refused = j2kdec("-i '" + input.string() + "' -o '" + (scratch / name).string() + "'", scratch.path());
    EXPECT_EQ(refused.exit_code, 1) << name;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    EXPECT_NE(refused.err.find("bits"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(scratch / name)) << name;
  }
}
