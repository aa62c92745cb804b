// Tests for the dwtool command-line tool, run as a subprocess the way scripts use it: round trips
// through files, agreement with calling the CPU backend directly, and the failure contract (exit
// code, exactly one "dwtool: " line on stderr, no output file left behind).

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "dwt/params.h"
#include "dwt/plane.h"
#include "dwt_cpu/cpu_backend.h"
#include "imageio/image.h"
#include "imageio/pfm.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "testimages/patterns.h"

#ifndef DWTOOL_PATH
#error "DWTOOL_PATH must name the dwtool binary (see tests/CMakeLists.txt)"
#endif

extern char** environ;

namespace fs = std::filesystem;

namespace {

struct RunResult {
  int exit_code = -1;  // -1 also when dwtool died from a signal
  std::string err;     // everything dwtool wrote to stderr
};

// Spawns dwtool with `args`, stdout discarded and stderr captured through a pipe. Only one stream
// is captured, so reading it to EOF before waiting cannot deadlock.
RunResult run_dwtool(const std::vector<std::string>& args) {
  std::vector<std::string> all{DWTOOL_PATH};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return {};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);  // dup2 clears O_CLOEXEC on fd 2
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);

  RunResult result;
  if (spawned != 0) {
    ::close(fds[0]);
    result.err = "posix_spawn failed";
    return result;
  }
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      result.err.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::vector<std::string> forward_args(const std::string& in, const std::string& out) {
  return {"forward", "-i", in, "-o", out};
}

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

imageio::Image as_float(const imageio::Image& image) {
  imageio::Image f = image;
  f.is_float = true;
  f.is_signed = false;
  f.bits_per_sample = 32;
  return f;
}

// Floats compared by their bits, so -0.0 vs 0.0 or NaN would not pass unnoticed.
void expect_bit_identical(const std::vector<float>& expected, const std::vector<float>& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (std::bit_cast<std::uint32_t>(expected[i]) != std::bit_cast<std::uint32_t>(actual[i])) {
      if (++mismatches <= 5) ADD_FAILURE() << "sample " << i << ": expected " << expected[i] << ", got " << actual[i];
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

float max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  float worst = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

// A fresh directory per test, removed afterwards, so a test can check that a failed run left
// nothing behind.
class DwtoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("dwtool_test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::set<std::string> files_in_dir() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.insert(entry.path().filename().string());
    return names;
  }

  // An 8-bit greyscale test image written to `name` (format from the extension).
  imageio::Image write_test_image(const std::string& name, int width, int height,
                                  testimages::Pattern pattern = testimages::Pattern::Mix) {
    const imageio::Image image = testimages::generate(pattern, width, height, 1, 8);
    imageio::write_image(path(name), image);
    return image;
  }

  // The failure contract: non-zero exit, exactly one line on stderr that starts with "dwtool: ",
  // and the directory holds exactly what it held before (no output, no temporary file).
  RunResult expect_failure(const std::vector<std::string>& args, const std::string& output) {
    const std::set<std::string> before = files_in_dir();
    const RunResult r = run_dwtool(args);
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_NE(r.exit_code, -1) << "dwtool crashed: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << r.err;
    EXPECT_EQ(r.err.rfind("dwtool: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(output)) << output;
    EXPECT_EQ(files_in_dir(), before);
    return r;
  }

  fs::path dir_;
};

TEST_F(DwtoolTest, Reversible53RoundTripOfPngIsExact) {
  const imageio::Image original = write_test_image("in.png", 127, 129);
  const std::vector<std::string> common{"--kernel", "53", "--origin", "1,1"};

  RunResult r = run_dwtool(with(forward_args(path("in.png"), path("c.pfm")), common));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const imageio::Image coefficients = imageio::read_pfm(path("c.pfm"));
  ASSERT_EQ(coefficients.width, 127);
  ASSERT_EQ(coefficients.height, 129);
  ASSERT_EQ(coefficients.channels, 1);
  for (float c : coefficients.pixels) ASSERT_EQ(std::trunc(c), c) << "5/3 coefficients are integers";
  EXPECT_NE(coefficients.pixels, original.pixels);

  r = run_dwtool(with({"inverse", "-i", path("c.pfm"), "-o", path("out.png")}, common));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const imageio::Image back = imageio::read_greyscale(path("out.png"));
  EXPECT_EQ(back.bits_per_sample, 8);
  EXPECT_EQ(back.width, 127);
  EXPECT_EQ(back.height, 129);
  EXPECT_EQ(back.pixels, original.pixels);
}

TEST_F(DwtoolTest, Irreversible97RoundTripOfPgmToPfmIsClose) {
  const imageio::Image original = write_test_image("in.pgm", 100, 75);
  RunResult r = run_dwtool(forward_args(path("in.pgm"), path("c.pfm")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_dwtool({"inverse", "-i", path("c.pfm"), "-o", path("out.pfm")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const imageio::Image back = imageio::read_pfm(path("out.pfm"));
  ASSERT_EQ(back.width, 100);
  ASSERT_EQ(back.height, 75);
  EXPECT_LE(max_abs_difference(back.pixels, original.pixels), 0.05f);
}

TEST_F(DwtoolTest, Irreversible97RoundTripOfPfmInputWithPeriodicBoundaryIsClose) {
  const imageio::Image original = as_float(testimages::generate(testimages::Pattern::ZonePlate, 96, 64, 1, 8));
  imageio::write_pfm(path("in.pfm"), original);
  // Periodic extension reconstructs perfectly only when every transformed length is even: 96 and 64
  // stay even for 3 levels, also with the odd x origin.
  const std::vector<std::string> common{"--boundary", "per", "--origin", "1,0", "--levels", "3"};
  RunResult r = run_dwtool(with(forward_args(path("in.pfm"), path("c.pfm")), common));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_dwtool(with({"inverse", "-i", path("c.pfm"), "-o", path("out.pfm")}, common));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LE(max_abs_difference(imageio::read_pfm(path("out.pfm")).pixels, original.pixels), 0.05f);
}

TEST_F(DwtoolTest, ForwardMatchesCpuBackendBitForBit) {
  const imageio::Image image = write_test_image("in.png", 61, 47);
  dwt_cpu::CpuBackend backend;
  for (const char* kernel : {"97", "53f", "haar", "53"}) {
    SCOPED_TRACE(kernel);
    dwt::DwtParams params;
    params.kernel = dwt::parse_kernel(kernel);
    params.boundary = dwt::Boundary::Periodic;
    params.levels = 3;
    params.origin = {1, 2};

    std::vector<float> expected = image.pixels;
    if (dwt::get_kernel(params.kernel).reversible) {
      std::vector<std::int32_t> plane(image.pixels.begin(), image.pixels.end());
      backend.forward(dwt::make_span(plane.data(), image.width, image.height), params);
      expected.assign(plane.begin(), plane.end());
    } else {
      backend.forward(dwt::make_span(expected.data(), image.width, image.height), params);
    }

    const RunResult r = run_dwtool(with(forward_args(path("in.png"), path("c.pfm")),
                                        {"--kernel", kernel, "--boundary", "per", "--levels", "3", "--origin", "1,2"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_bit_identical(expected, imageio::read_pfm(path("c.pfm")).pixels);
  }
}

TEST_F(DwtoolTest, InverseMatchesCpuBackendBitForBit) {
  const imageio::Image coefficients = as_float(testimages::generate(testimages::Pattern::Noise, 40, 33, 1, 8));
  imageio::write_pfm(path("c.pfm"), coefficients);
  dwt::DwtParams params;
  params.levels = 4;
  params.boundary = dwt::Boundary::Zero;
  std::vector<float> expected = coefficients.pixels;
  dwt_cpu::CpuBackend().inverse(dwt::make_span(expected.data(), 40, 33), params);

  const RunResult r =
      run_dwtool({"inverse", "-i", path("c.pfm"), "-o", path("out.pfm"), "--levels", "4", "--boundary", "zero"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_bit_identical(expected, imageio::read_pfm(path("out.pfm")).pixels);
}

TEST_F(DwtoolTest, SuccessPrintsOneSummaryLineAndQuietNothing) {
  write_test_image("in.png", 64, 48);
  RunResult r = run_dwtool(with(forward_args(path("in.png"), path("c.pfm")), {"--threads", "2"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("forward 97 sym 5 levels 64x48 origin (0,0) on cpu lifting (", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("2 threads): "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" ms\n"), std::string::npos) << r.err;

  r = run_dwtool(with(forward_args(path("in.png"), path("q.pfm")), {"--quiet"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(fs::exists(path("q.pfm")));
}

TEST_F(DwtoolTest, IntegerOutputIsRoundedAndClampedWithOneNotice) {
  // Zero levels is the identity, so the coefficients are the output samples.
  imageio::Image plane = as_float(testimages::generate(testimages::Pattern::GradientH, 4, 1, 1, 8));
  plane.pixels = {-3.0f, 300.0f, 12.4f, 12.6f};
  imageio::write_pfm(path("c.pfm"), plane);

  RunResult r = run_dwtool({"inverse", "-i", path("c.pfm"), "-o", path("out.png"), "--levels", "0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;  // the notice and the summary
  EXPECT_NE(r.err.find("2 samples clamped to [0, 255]"), std::string::npos) << r.err;
  EXPECT_EQ(imageio::read_greyscale(path("out.png")).pixels, (std::vector<float>{0, 255, 12, 13}));

  r = run_dwtool({"inverse", "-i", path("c.pfm"), "-o", path("out16.png"), "--levels", "0", "--bits", "16", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const imageio::Image wide = imageio::read_greyscale(path("out16.png"));
  EXPECT_EQ(wide.bits_per_sample, 16);
  EXPECT_EQ(wide.pixels, (std::vector<float>{0, 300, 12, 13}));
}

TEST_F(DwtoolTest, MissingInputIsNamed) {
  const RunResult r = expect_failure(forward_args(path("absent.png"), path("c.pfm")), path("c.pfm"));
  EXPECT_NE(r.err.find(path("absent.png")), std::string::npos) << r.err;
  EXPECT_EQ(r.exit_code, 1);
}

TEST_F(DwtoolTest, RgbInputIsRefused) {
  imageio::write_image(path("rgb.png"), testimages::generate(testimages::Pattern::Mix, 16, 16, 3, 8));
  const RunResult r = expect_failure(forward_args(path("rgb.png"), path("c.pfm")), path("c.pfm"));
  EXPECT_NE(r.err.find(path("rgb.png")), std::string::npos) << r.err;
}

TEST_F(DwtoolTest, UnknownKernelBoundaryBackendAreRefused) {
  write_test_image("in.png", 16, 16);
  const auto args = forward_args(path("in.png"), path("c.pfm"));
  EXPECT_NE(expect_failure(with(args, {"--kernel", "79"}), path("c.pfm")).err.find("79"), std::string::npos);
  expect_failure(with(args, {"--boundary", "mirror"}), path("c.pfm"));
  expect_failure(with(args, {"--backend", "tpu"}), path("c.pfm"));
  expect_failure(with(args, {"--gl", "glx"}), path("c.pfm"));
  expect_failure(with(args, {"--threads", "-1"}), path("c.pfm"));
}

TEST_F(DwtoolTest, TooManyLevelsIsRefused) {
  write_test_image("in.png", 16, 16);
  const RunResult r =
      expect_failure(with(forward_args(path("in.png"), path("c.pfm")), {"--levels", "40"}), path("c.pfm"));
  EXPECT_NE(r.err.find(path("in.png")), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("40 levels"), std::string::npos) << r.err;
}

TEST_F(DwtoolTest, ForwardOutputMustBePfm) {
  write_test_image("in.png", 16, 16);
  const RunResult r = expect_failure(forward_args(path("in.png"), path("c.png")), path("c.png"));
  EXPECT_EQ(r.err, "dwtool: " + path("c.png") + ": forward output must be a .pfm file\n");
}

TEST_F(DwtoolTest, MalformedOriginIsRefused) {
  write_test_image("in.png", 16, 16);
  for (const char* origin : {"1,", "1", ",1", "-1,2", "1,-2", "+1,2", "1,2,3", " 1,2", "1, 2", "a,b", "1.5,2", ""}) {
    SCOPED_TRACE(origin);
    expect_failure(with(forward_args(path("in.png"), path("c.pfm")), {"--origin", origin}), path("c.pfm"));
  }
}

TEST_F(DwtoolTest, ZeroByteInputIsRefused) {
  for (const char* name : {"empty.png", "empty.pfm"}) {
    SCOPED_TRACE(name);
    std::ofstream(path(name), std::ios::binary).close();
    const RunResult r = expect_failure(forward_args(path(name), path("c.pfm")), path("c.pfm"));
    EXPECT_NE(r.err.find(path(name)), std::string::npos) << r.err;
  }
  const RunResult r = expect_failure({"inverse", "-i", path("empty.pfm"), "-o", path("out.png")}, path("out.png"));
  EXPECT_NE(r.err.find(path("empty.pfm")), std::string::npos) << r.err;
}

TEST_F(DwtoolTest, TruncatedPfmIsRefused) {
  imageio::write_pfm(path("whole.pfm"), as_float(testimages::generate(testimages::Pattern::Mix, 32, 32, 1, 8)));
  fs::copy_file(path("whole.pfm"), path("cut.pfm"));
  fs::resize_file(path("cut.pfm"), fs::file_size(path("whole.pfm")) / 2);
  RunResult r = expect_failure(forward_args(path("cut.pfm"), path("c.pfm")), path("c.pfm"));
  EXPECT_NE(r.err.find(path("cut.pfm")), std::string::npos) << r.err;
  r = expect_failure({"inverse", "-i", path("cut.pfm"), "-o", path("out.pfm")}, path("out.pfm"));
  EXPECT_NE(r.err.find(path("cut.pfm")), std::string::npos) << r.err;
}

TEST_F(DwtoolTest, ReversibleKernelOnGpuIsRefused) {
  write_test_image("in.png", 16, 16);
  const RunResult r = expect_failure(
      with(forward_args(path("in.png"), path("c.pfm")), {"--backend", "gpu", "--kernel", "53"}), path("c.pfm"));
  EXPECT_EQ(r.err, "dwtool: the reversible 5/3 runs on the CPU backend only\n");
}

TEST_F(DwtoolTest, ReversibleKernelNeedsIntegers) {
  imageio::Image plane = as_float(testimages::generate(testimages::Pattern::Mix, 8, 8, 1, 8));
  plane.pixels[9] = 2.5f;
  imageio::write_pfm(path("frac.pfm"), plane);
  RunResult r = expect_failure(with(forward_args(path("frac.pfm"), path("c.pfm")), {"--kernel", "53", "--levels", "2"}),
                               path("c.pfm"));
  EXPECT_NE(r.err.find(path("frac.pfm")), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(1,1)"), std::string::npos) << r.err;
  r = expect_failure({"inverse", "-i", path("frac.pfm"), "-o", path("out.png"), "--kernel", "53", "--levels", "2"},
                     path("out.png"));
  EXPECT_NE(r.err.find(path("frac.pfm")), std::string::npos) << r.err;
}

TEST_F(DwtoolTest, InverseInputMustBeOneChannelPfm) {
  write_test_image("in.png", 16, 16);
  expect_failure({"inverse", "-i", path("in.png"), "-o", path("out.png")}, path("out.png"));
  imageio::write_pfm(path("rgb.pfm"), as_float(testimages::generate(testimages::Pattern::Mix, 8, 8, 3, 8)));
  expect_failure({"inverse", "-i", path("rgb.pfm"), "-o", path("out.png")}, path("out.png"));
}

TEST_F(DwtoolTest, UsageErrorsAreOneLineWithExitCode2) {
  write_test_image("in.png", 16, 16);
  const auto args = forward_args(path("in.png"), path("c.pfm"));
  EXPECT_EQ(expect_failure(with(args, {"--frobnicate"}), path("c.pfm")).exit_code, 2);
  EXPECT_EQ(expect_failure({"forward", "-i", path("in.png")}, path("c.pfm")).exit_code, 2);
  EXPECT_EQ(expect_failure(with(args, {"--levels", "many"}), path("c.pfm")).exit_code, 2);
  EXPECT_EQ(expect_failure({}, path("c.pfm")).exit_code, 2);
  // --bits concerns integer output images, which forward never writes.
  EXPECT_EQ(expect_failure(with(args, {"--bits", "8"}), path("c.pfm")).exit_code, 2);
}

TEST_F(DwtoolTest, GpuForwardMatchesCpu) {
  write_test_image("in.png", 64, 48);
  RunResult r = run_dwtool(with(forward_args(path("in.png"), path("cpu.pfm")), {"--backend", "cpu"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_dwtool(with(forward_args(path("in.png"), path("gpu.pfm")), {"--backend", "gpu"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("dwtool: renderer: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" on gpu "), std::string::npos) << r.err;
  EXPECT_LE(max_abs_difference(imageio::read_pfm(path("gpu.pfm")).pixels, imageio::read_pfm(path("cpu.pfm")).pixels),
            1e-4f * 255);
}

}  // namespace
