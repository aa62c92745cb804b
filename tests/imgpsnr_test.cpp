// imgpsnr: the PSNR computation against cases worked out by hand, and the command line from outside
// (text and JSON output, "inf" for identical images, one-line errors with exit status 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <sys/wait.h>

#include "imageio/image.h"
#include "imageio/write.h"
#include "psnr.h"

namespace {

namespace fs = std::filesystem;
constexpr double kInf = std::numeric_limits<double>::infinity();

imageio::Image image(int width, int height, int channels, int bits, std::vector<float> pixels) {
  imageio::Image im;
  im.width = width;
  im.height = height;
  im.channels = channels;
  im.bits_per_sample = bits;
  im.pixels = std::move(pixels);
  return im;
}

// ---------------------------------------------------------------- the computation

TEST(Psnr, PeakForBits) {
  EXPECT_EQ(cli::peak_for_bits(1), 1.0);
  EXPECT_EQ(cli::peak_for_bits(8), 255.0);
  EXPECT_EQ(cli::peak_for_bits(12), 4095.0);
  EXPECT_EQ(cli::peak_for_bits(16), 65535.0);
  EXPECT_EQ(cli::peak_for_bits(32), 4294967295.0);
  EXPECT_THROW(cli::peak_for_bits(0), std::invalid_argument);
  EXPECT_THROW(cli::peak_for_bits(33), std::invalid_argument);
}

// 2x2 grey, one sample off by 2: MSE = 2^2 / 4 = 1, so PSNR = 10 log10(255^2 / 1) = 20 log10(255).
TEST(Psnr, OneSampleOffByTwoGivesMseOne) {
  const auto ref = image(2, 2, 1, 8, {10, 20, 30, 40});
  const auto test = image(2, 2, 1, 8, {10, 22, 30, 40});
  const cli::PsnrResult r = cli::psnr(ref, test, 8);
  ASSERT_EQ(r.channel_db.size(), 1u);
  EXPECT_DOUBLE_EQ(r.channel_mse[0], 1.0);
  EXPECT_DOUBLE_EQ(r.all_mse, 1.0);
  EXPECT_NEAR(r.channel_db[0], 20.0 * std::log10(255.0), 1e-12);
  EXPECT_NEAR(r.all_db, 48.130803608679102, 1e-9);
  EXPECT_EQ(r.peak, 255.0);
}

// 2x2 RGB. Channel 0 identical (MSE 0, inf); channel 1 every sample off by 1 (MSE 1); channel 2 one
// sample off by 4 (MSE 16/4 = 4). Over all 12 samples: (0 + 4 + 16) / 12 = 5/3.
TEST(Psnr, PerChannelAndOverallByHand) {
  const auto ref = image(2, 2, 3, 8, {0, 0, 0, 100, 100, 100, 200, 200, 200, 255, 255, 255});
  const auto test = image(2, 2, 3, 8, {0, 1, 4, 100, 99, 100, 200, 201, 200, 255, 254, 255});
  const cli::PsnrResult r = cli::psnr(ref, test, 8);
  ASSERT_EQ(r.channel_db.size(), 3u);
  EXPECT_EQ(r.channel_mse[0], 0.0);
  EXPECT_EQ(r.channel_db[0], kInf);
  EXPECT_DOUBLE_EQ(r.channel_mse[1], 1.0);
  EXPECT_NEAR(r.channel_db[1], 20.0 * std::log10(255.0), 1e-12);
  EXPECT_DOUBLE_EQ(r.channel_mse[2], 4.0);
  EXPECT_NEAR(r.channel_db[2], 20.0 * std::log10(255.0) - 20.0 * std::log10(2.0), 1e-12);  // 42.1102 dB
  EXPECT_DOUBLE_EQ(r.all_mse, 5.0 / 3.0);
  EXPECT_NEAR(r.all_db, 10.0 * std::log10(255.0 * 255.0 * 3.0 / 5.0), 1e-12);
}

TEST(Psnr, IsSymmetricInItsImages) {
  const auto a = image(2, 1, 1, 8, {0, 10});
  const auto b = image(2, 1, 1, 8, {3, 6});
  const auto ab = cli::psnr(a, b, 8), ba = cli::psnr(b, a, 8);
  EXPECT_DOUBLE_EQ(ab.all_mse, 12.5);  // (9 + 16) / 2
  EXPECT_DOUBLE_EQ(ab.all_db, ba.all_db);
}

// The peak follows the bits asked for: every sample off by 1 at 16 bits is 20 log10(65535).
TEST(Psnr, BitsSetThePeak) {
  const auto ref = image(1, 2, 1, 16, {0, 65535});
  const auto test = image(1, 2, 1, 16, {1, 65534});
  EXPECT_NEAR(cli::psnr(ref, test, 16).all_db, 20.0 * std::log10(65535.0), 1e-12);
  EXPECT_NEAR(cli::psnr(ref, test, 8).all_db, 20.0 * std::log10(255.0), 1e-12);
  EXPECT_NEAR(cli::psnr_with_peak(ref, test, 1.0).all_db, 0.0, 1e-12);
  EXPECT_THROW(cli::psnr_with_peak(ref, test, 0.0), std::invalid_argument);
}

TEST(Psnr, IdenticalImagesAreInfinite) {
  const auto ref = image(3, 2, 3, 8, std::vector<float>(18, 77.0f));
  const cli::PsnrResult r = cli::psnr(ref, ref, 8);
  for (double db : r.channel_db) EXPECT_EQ(db, kInf);
  EXPECT_EQ(r.all_db, kInf);
  EXPECT_EQ(r.all_mse, 0.0);
}

TEST(Psnr, MismatchedShapesAreOneLineErrors) {
  const auto ref = image(2, 2, 1, 8, {1, 2, 3, 4});
  const auto wider = image(4, 1, 1, 8, {1, 2, 3, 4});
  const auto rgb = image(2, 2, 3, 8, std::vector<float>(12, 0.0f));
  for (const auto* other : {&wider, &rgb}) {
    try {
      cli::psnr(ref, *other, 8);
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find("differ"), std::string::npos) << what;
    }
  }
  EXPECT_THROW(cli::psnr(image(0, 0, 1, 8, {}), image(0, 0, 1, 8, {}), 8), std::invalid_argument);
}

// ---------------------------------------------------------------- the command line

struct ProcessResult {
  int exit_code = 0;
  std::string out, err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

class ImgpsnrCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device rd;
    dir = fs::temp_directory_path() / ("imgpsnr_test_" + std::to_string(rd()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  ProcessResult run(const std::string& args) {
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string cmd =
        std::string("'") + IMGPSNR_PATH + "' " + args + " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  std::string write(const std::string& name, const imageio::Image& im) {
    const fs::path path = dir / name;
    imageio::write_image(path.string(), im);
    return "'" + path.string() + "'";
  }

  fs::path dir;
};

TEST_F(ImgpsnrCli, PrintsTheHandComputedCase) {
  const auto ref = write("ref.png", image(2, 2, 3, 8, {0, 0, 0, 100, 100, 100, 200, 200, 200, 255, 255, 255}));
  const auto test = write("test.png", image(2, 2, 3, 8, {0, 1, 4, 100, 99, 100, 200, 201, 200, 255, 254, 255}));
  const ProcessResult r = run(ref + " " + test);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("peak 255 (8 bits)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("channel 0: PSNR inf dB, MSE 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("channel 1: PSNR 48.1308 dB, MSE 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("channel 2: PSNR 42.1102 dB, MSE 4\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("all: PSNR 45.9123 dB, MSE 1.66667\n"), std::string::npos) << r.out;

  const ProcessResult j = run(ref + " " + test + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_EQ(std::count(j.out.begin(), j.out.end(), '\n'), 1) << j.out;
  EXPECT_NE(j.out.find("\"width\": 2, \"height\": 2, \"channels\": 3, \"bits\": 8, \"peak\": 255"), std::string::npos)
      << j.out;
  EXPECT_NE(j.out.find("\"channel_db\": [\"inf\", 48.130804, 42.110204]"), std::string::npos) << j.out;
  EXPECT_NE(j.out.find("\"all_db\": 45.912316"), std::string::npos) << j.out;
}

TEST_F(ImgpsnrCli, IdenticalImagesPrintInf) {
  const auto ref = write("same.png", image(3, 2, 1, 8, {1, 2, 3, 4, 5, 6}));
  const ProcessResult r = run(ref + " " + ref);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("channel 0: PSNR inf dB, MSE 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("all: PSNR inf dB, MSE 0\n"), std::string::npos) << r.out;
  const ProcessResult j = run(ref + " " + ref + " --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_NE(j.out.find("\"all_db\": \"inf\", \"all_mse\": 0}"), std::string::npos) << j.out;
}

// Bits come from the reference (16-bit PNG: peak 65535) unless --bits says otherwise.
TEST_F(ImgpsnrCli, BitsFromTheReferenceOrTheOption) {
  const auto ref = write("ref16.png", image(1, 2, 1, 16, {0, 65535}));
  const auto test = write("test16.png", image(1, 2, 1, 16, {1, 65534}));
  const ProcessResult r = run(ref + " " + test);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("peak 65535 (16 bits)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("all: PSNR 96.3295 dB, MSE 1\n"), std::string::npos) << r.out;
  const ProcessResult b = run(ref + " " + test + " --bits 8");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.out.find("all: PSNR 48.1308 dB, MSE 1\n"), std::string::npos) << b.out;
}

TEST_F(ImgpsnrCli, ErrorsAreOneLineWithExitOne) {
  const auto ref = write("a.png", image(2, 2, 1, 8, {1, 2, 3, 4}));
  const auto wide = write("b.png", image(4, 1, 1, 8, {1, 2, 3, 4}));
  const auto rgb = write("c.png", image(2, 2, 3, 8, std::vector<float>(12, 9.0f)));
  const std::string missing = "'" + (dir / "missing.png").string() + "'";
  for (const std::string& args : {ref + " " + wide, ref + " " + rgb, ref + " " + missing, missing + " " + ref}) {
    SCOPED_TRACE(args);
    const ProcessResult r = run(args);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("imgpsnr: ", 0), 0u) << r.err;
  }
  const ProcessResult shape = run(ref + " " + wide);
  EXPECT_NE(shape.err.find("reference is 2x2 with 1 channel, test is 4x1 with 1 channel"), std::string::npos)
      << shape.err;
  // Usage errors are one line too (exit 2, as the project's other tools).
  const ProcessResult usage = run(ref);
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(std::count(usage.err.begin(), usage.err.end(), '\n'), 1) << usage.err;
}

}  // namespace
