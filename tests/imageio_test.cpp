// Tests for imageio: exact PFM and OpenImageIO round trips, strict PFM header
// validation, one-line "PATH: problem" errors and atomic writes.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

#include "imageio/image.h"
#include "imageio/pfm.h"
#include "imageio/read.h"
#include "imageio/write.h"

namespace fs = std::filesystem;

namespace {

// A fresh directory per test, removed afterwards, so tests can check that
// nothing but the expected files was left behind.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("imageio_test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::vector<std::string> files_in_dir() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

  fs::path dir_;
};

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

imageio::Image make_image(int width, int height, int channels, int bits, bool is_signed) {
  imageio::Image image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.bits_per_sample = bits;
  image.is_signed = is_signed;
  image.pixels.resize(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  return image;
}

// Integer image whose samples sweep the whole range of `bits`, including both
// ends, in an order that differs per position so misplaced samples show up.
imageio::Image integer_image(int width, int height, int channels, int bits, bool is_signed) {
  imageio::Image image = make_image(width, height, channels, bits, is_signed);
  const std::int64_t levels = std::int64_t{1} << bits;
  const std::int64_t low = is_signed ? -(levels / 2) : 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    std::int64_t level = std::int64_t(i * 7919) % levels;
    if (i == 0) level = 0;
    if (i == 1) level = levels - 1;
    image.pixels[i] = float(low + level);
  }
  return image;
}

imageio::Image float_image(int width, int height, int channels) {
  imageio::Image image = make_image(width, height, channels, 32, false);
  image.is_float = true;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = (float(i) - 3.25f) * 0.1f;
  }
  if (image.pixels.size() > 3) {
    image.pixels[1] = std::numeric_limits<float>::max();
    image.pixels[2] = std::numeric_limits<float>::denorm_min();
    image.pixels[3] = -0.0f;
  }
  return image;
}

// Compares bit patterns, so that -0.0 versus 0.0 counts as a difference.
void expect_same_pixels(const imageio::Image& expected, const imageio::Image& actual) {
  ASSERT_EQ(expected.width, actual.width);
  ASSERT_EQ(expected.height, actual.height);
  ASSERT_EQ(expected.channels, actual.channels);
  ASSERT_EQ(expected.pixels.size(), actual.pixels.size());
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(expected.pixels[i]), std::bit_cast<std::uint32_t>(actual.pixels[i]))
        << "sample " << i << ": expected " << expected.pixels[i] << ", got " << actual.pixels[i];
  }
}

// Runs `action`, which must throw IoError whose one-line message starts with
// "PATH: ". Returns the message for further checks.
template <typename Action>
std::string expect_io_error(const std::string& path, Action action) {
  try {
    action();
  } catch (const imageio::IoError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(e.path(), path);
    return message;
  }
  ADD_FAILURE() << "expected IoError for " << path;
  return {};
}

std::string le_float(float value) {
  const std::uint32_t word = std::bit_cast<std::uint32_t>(value);
  std::string out;
  for (int shift = 0; shift < 32; shift += 8) out += char((word >> shift) & 0xff);
  return out;
}

// ---------------------------------------------------------------- PFM

TEST_F(ImageIoTest, PfmRoundTripIsExact) {
  for (const auto& [width, height, channels] :
       std::vector<std::tuple<int, int, int>>{{1, 1, 1}, {5, 3, 1}, {7, 1, 3}, {3, 9, 3}}) {
    const imageio::Image original = float_image(width, height, channels);
    const std::string file = path("round.pfm");
    imageio::write_pfm(file, original);
    const imageio::Image back = imageio::read_pfm(file);
    EXPECT_TRUE(back.is_float);
    EXPECT_EQ(back.bits_per_sample, 32);
    expect_same_pixels(original, back);
    // read_image and write_image route .pfm here too.
    expect_same_pixels(original, imageio::read_image(file));
  }
}

TEST_F(ImageIoTest, PfmStoresBottomRowFirst) {
  imageio::Image image = make_image(2, 3, 1, 32, false);
  image.is_float = true;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 2; ++x) image.at(x, y, 0) = float(10 * y + x);
  }
  const std::string file = path("orient.pfm");
  imageio::write_pfm(file, image);

  const std::vector<std::uint8_t> bytes = read_bytes(file);
  const std::string header = "Pf\n2 3\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(header.size())), header);
  const std::string data(bytes.begin() + std::ptrdiff_t(header.size()), bytes.end());
  EXPECT_EQ(data, le_float(20) + le_float(21) + le_float(10) + le_float(11) + le_float(0) + le_float(1));

  const imageio::Image back = imageio::read_pfm(file);
  EXPECT_EQ(back.at(0, 0, 0), 0.0f);
  EXPECT_EQ(back.at(1, 2, 0), 21.0f);
}

TEST_F(ImageIoTest, PfmReadsBigEndian) {
  // Positive scale means big-endian; 1.0f is 3f 80 00 00.
  const std::string file = path("big.pfm");
  write_bytes(file,
              std::string("Pf\n2 1\n1.0\n") + std::string("\x3f\x80\x00\x00", 4) + std::string("\xc0\x00\x00\x00", 4));
  const imageio::Image image = imageio::read_pfm(file);
  EXPECT_EQ(image.at(0, 0, 0), 1.0f);
  EXPECT_EQ(image.at(1, 0, 0), -2.0f);
}

TEST_F(ImageIoTest, PfmExtensionIsCaseInsensitive) {
  const std::string file = path("upper.PFM");
  imageio::write_image(file, float_image(3, 2, 1));
  const std::vector<std::uint8_t> bytes = read_bytes(file);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(bytes[0], 'P');
  EXPECT_EQ(bytes[1], 'f');
  expect_same_pixels(float_image(3, 2, 1), imageio::read_image(file));
}

TEST_F(ImageIoTest, PfmWritesIntegerImagesAsFloat) {
  const imageio::Image original = integer_image(4, 3, 3, 16, true);
  const std::string file = path("ints.pfm");
  imageio::write_image(file, original);
  const imageio::Image back = imageio::read_image(file);
  EXPECT_TRUE(back.is_float);
  EXPECT_EQ(back.pixels, original.pixels);
}

TEST_F(ImageIoTest, MalformedPfmIsRejected) {
  const std::string pixels4 = le_float(1) + le_float(2) + le_float(3) + le_float(4);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty", ""},
      {"bad_magic", "P6\n2 2\n-1.0\n" + pixels4},
      {"garbage_after_magic", "PFx\n2 2\n-1.0\n" + pixels4},
      {"digit_after_magic", "Pf2 2\n-1.0\n" + pixels4},
      {"zero_width", "Pf\n0 2\n-1.0\n" + pixels4},
      {"negative_height", "Pf\n2 -2\n-1.0\n" + pixels4},
      {"non_numeric_width", "Pf\nabc 2\n-1.0\n" + pixels4},
      {"width_with_junk", "Pf\n2x 2\n-1.0\n" + pixels4},
      {"width_overflow", "Pf\n99999999999999999999999 2\n-1.0\n" + pixels4},
      {"huge_dimensions", "PF\n100000000 100000000\n-1.0\n" + pixels4},
      {"too_many_samples", "Pf\n65536 32769\n-1.0\n" + pixels4},
      {"scale_zero", "Pf\n2 2\n0\n" + pixels4},
      {"scale_nan", "Pf\n2 2\nnan\n" + pixels4},
      {"scale_inf", "Pf\n2 2\n-inf\n" + pixels4},
      {"scale_text", "Pf\n2 2\nbig\n" + pixels4},
      {"missing_scale", "Pf\n2 2"},
      {"header_only", "Pf\n2 2\n-1.0"},
      {"truncated_data", "Pf\n2 2\n-1.0\n" + pixels4.substr(0, 13)},
      {"no_data", "Pf\n2 2\n-1.0\n"},
      {"trailing_data", "Pf\n2 2\n-1.0\n" + pixels4 + "x"},
      {"rgb_truncated", "PF\n2 2\n-1.0\n" + pixels4},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const std::string file = path(name + ".pfm");
    write_bytes(file, bytes);
    expect_io_error(file, [&] { imageio::read_pfm(file); });
    expect_io_error(file, [&] { imageio::read_image(file); });
    // The parser itself, as the fuzzer calls it.
    const std::vector<std::uint8_t> raw(bytes.begin(), bytes.end());
    expect_io_error("mem", [&] { imageio::parse_pfm(raw, "mem"); });
  }
}

TEST_F(ImageIoTest, PfmErrorsSayWhatIsWrong) {
  const std::string file = path("huge.pfm");
  write_bytes(file, "PF\n100000000 100000000\n-1.0\n");
  EXPECT_NE(expect_io_error(file, [&] { imageio::read_pfm(file); }).find("too large"), std::string::npos);

  write_bytes(file, "Pf\n2 2\n-1.0\n" + le_float(1));
  EXPECT_NE(expect_io_error(file, [&] { imageio::read_pfm(file); }).find("truncated"), std::string::npos);
}

TEST_F(ImageIoTest, PfmWriteRejectsOtherChannelCounts) {
  const std::string file = path("four.pfm");
  expect_io_error(file, [&] { imageio::write_pfm(file, float_image(2, 2, 4)); });
  EXPECT_TRUE(files_in_dir().empty());
}

// ---------------------------------------------------------------- OpenImageIO

TEST_F(ImageIoTest, Png8BitRoundTripIsExact) {
  for (int channels : {1, 2, 3, 4}) {
    SCOPED_TRACE(channels);
    const imageio::Image original = integer_image(13, 7, channels, 8, false);
    const std::string file = path("eight.png");
    imageio::write_image(file, original);
    const imageio::Image back = imageio::read_image(file);
    EXPECT_EQ(back.bits_per_sample, 8);
    EXPECT_FALSE(back.is_signed);
    EXPECT_FALSE(back.is_float);
    // With 2 and 4 channels the last one is alpha: values must not be
    // premultiplied or un-premultiplied on the way.
    expect_same_pixels(original, back);
  }
}

TEST_F(ImageIoTest, Png16BitRoundTripIsExact) {
  for (int channels : {1, 3, 4}) {
    SCOPED_TRACE(channels);
    const imageio::Image original = integer_image(9, 11, channels, 16, false);
    const std::string file = path("sixteen.png");
    imageio::write_image(file, original);
    const imageio::Image back = imageio::read_image(file);
    EXPECT_EQ(back.bits_per_sample, 16);
    expect_same_pixels(original, back);
  }
}

TEST_F(ImageIoTest, TwelveBitImageIsStoredIn16BitPng) {
  const imageio::Image original = integer_image(5, 5, 1, 12, false);
  const std::string file = path("twelve.png");
  imageio::write_image(file, original);
  const imageio::Image back = imageio::read_image(file);
  EXPECT_EQ(back.bits_per_sample, 16);
  expect_same_pixels(original, back);
}

TEST_F(ImageIoTest, TiffKeepsSignedAndFloatSamples) {
  for (int bits : {8, 16}) {
    SCOPED_TRACE(bits);
    const imageio::Image original = integer_image(6, 5, 3, bits, true);
    const std::string file = path("signed.tif");
    imageio::write_image(file, original);
    const imageio::Image back = imageio::read_image(file);
    EXPECT_TRUE(back.is_signed);
    EXPECT_EQ(back.bits_per_sample, bits);
    expect_same_pixels(original, back);
  }
  const imageio::Image original = float_image(4, 3, 1);
  const std::string file = path("float.tif");
  imageio::write_image(file, original);
  const imageio::Image back = imageio::read_image(file);
  EXPECT_TRUE(back.is_float);
  expect_same_pixels(original, back);
}

TEST_F(ImageIoTest, Pnm8BitRoundTripIsExact) {
  for (const auto& [name, channels] : std::vector<std::pair<std::string, int>>{{"grey.pgm", 1}, {"colour.ppm", 3}}) {
    const imageio::Image original = integer_image(7, 3, channels, 8, false);
    imageio::write_image(path(name), original);
    expect_same_pixels(original, imageio::read_image(path(name)));
  }
}

TEST_F(ImageIoTest, ReadGreyscaleAcceptsOnlyOneChannel) {
  const std::string grey = path("grey.png");
  imageio::write_image(grey, integer_image(4, 4, 1, 8, false));
  EXPECT_EQ(imageio::read_greyscale(grey).channels, 1);

  const std::string rgb = path("rgb.png");
  imageio::write_image(rgb, integer_image(4, 4, 3, 8, false));
  EXPECT_EQ(expect_io_error(rgb, [&] { imageio::read_greyscale(rgb); }),
            rgb + ": expected a greyscale image, found 3 channels");
}

TEST_F(ImageIoTest, MissingFileNamesThePath) {
  for (const std::string name : {"missing.png", "missing.pfm", "missing.tif"}) {
    const std::string file = path(name);
    expect_io_error(file, [&] { imageio::read_image(file); });
  }
}

TEST_F(ImageIoTest, CorruptFilesAreRejected) {
  const std::string garbage = path("garbage.png");
  write_bytes(garbage, "this is not a PNG file");
  expect_io_error(garbage, [&] { imageio::read_image(garbage); });

  // No truncated PNG here: OpenImageIO 2.4 leaks a string when libpng
  // aborts one (PNGInput::PngReadCallback longjmps past its destructor),
  // which would fail sanitizer builds. It is rejected all the same.
  for (const std::string name : {"cut.tif", "cut.pgm"}) {
    SCOPED_TRACE(name);
    const std::string good = path("good-" + name);
    imageio::write_image(good, integer_image(64, 64, name == "cut.pgm" ? 1 : 3, 8, false));
    const std::vector<std::uint8_t> bytes = read_bytes(good);
    const std::string truncated = path(name);
    write_bytes(truncated, std::string(bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() / 2)));
    expect_io_error(truncated, [&] { imageio::read_image(truncated); });
  }
}

TEST_F(ImageIoTest, UnsupportedSampleTypeIsRejected) {
  // A minimal little-endian TIFF holding one 32-bit unsigned grey sample.
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count, value;
  };
  const std::vector<Entry> entries = {
      {256, 3, 1, 1},   {257, 3, 1, 1}, {258, 3, 1, 32}, {259, 3, 1, 1}, {262, 3, 1, 1},
      {273, 4, 1, 134}, {277, 3, 1, 1}, {278, 3, 1, 1},  {279, 4, 1, 4}, {339, 3, 1, 1},
  };
  std::string tiff("II*\0\x08\0\0\0", 8);
  auto put = [&tiff](std::uint32_t value, int size) {
    for (int i = 0; i < size; ++i) tiff += char((value >> (8 * i)) & 0xff);
  };
  put(std::uint32_t(entries.size()), 2);
  for (const Entry& e : entries) {
    put(e.tag, 2);
    put(e.type, 2);
    put(e.count, 4);
    put(e.value, 4);
  }
  put(0, 4);  // no further IFD
  ASSERT_EQ(tiff.size(), 134u);
  put(123456789, 4);

  const std::string file = path("uint32.tif");
  write_bytes(file, tiff);
  EXPECT_NE(expect_io_error(file, [&] { imageio::read_image(file); }).find("unsupported sample type"),
            std::string::npos);
}

// ---------------------------------------------------------------- writing

TEST_F(ImageIoTest, WriteIntoMissingDirectoryLeavesNothing) {
  for (const std::string name : {"no/such/dir/out.png", "no/such/dir/out.pfm"}) {
    const std::string file = path(name);
    expect_io_error(file, [&] { imageio::write_image(file, integer_image(3, 3, 1, 8, false)); });
    EXPECT_FALSE(fs::exists(file));
  }
  EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIoTest, FormatThatCannotHoldTheSamplesIsAnError) {
  // PNG has no signed samples, BMP no 16-bit ones, EXR no integers: writing
  // would silently change values, so it must fail and leave no file.
  const std::vector<std::pair<std::string, imageio::Image>> cases = {
      {"signed.png", integer_image(4, 4, 1, 8, true)},
      {"sixteen.bmp", integer_image(4, 4, 3, 16, false)},
      {"eight.exr", integer_image(4, 4, 3, 8, false)},
  };
  for (const auto& [name, image] : cases) {
    SCOPED_TRACE(name);
    const std::string file = path(name);
    const imageio::Image& samples = image;  // Clang 14 cannot capture bindings
    expect_io_error(file, [&] { imageio::write_image(file, samples); });
  }
  EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIoTest, OutOfRangeOrFractionalSamplesAreAnError) {
  imageio::Image too_big = integer_image(3, 3, 1, 8, false);
  too_big.pixels[4] = 256;
  imageio::Image negative = integer_image(3, 3, 1, 12, false);
  negative.pixels[0] = -1;
  imageio::Image fraction = integer_image(3, 3, 1, 8, false);
  fraction.pixels[2] = 1.5f;
  imageio::Image wrong_size = integer_image(3, 3, 1, 8, false);
  wrong_size.pixels.pop_back();
  for (const auto* image : {&too_big, &negative, &fraction, &wrong_size}) {
    expect_io_error(path("bad.png"), [&] { imageio::write_image(path("bad.png"), *image); });
  }
  EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIoTest, FailedWriteKeepsThePreviousFile) {
  const std::string file = path("keep.png");
  write_bytes(file, "previous contents");
  expect_io_error(file, [&] { imageio::write_image(file, integer_image(4, 4, 1, 16, true)); });
  const std::vector<std::uint8_t> bytes = read_bytes(file);
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "previous contents");
  EXPECT_EQ(files_in_dir(), std::vector<std::string>{"keep.png"});
}

TEST_F(ImageIoTest, SuccessfulWriteReplacesAndLeavesNoTemporary) {
  const std::string file = path("replace.png");
  write_bytes(file, "previous contents");
  const imageio::Image image = integer_image(4, 4, 1, 8, false);
  imageio::write_image(file, image);
  expect_same_pixels(image, imageio::read_image(file));
  EXPECT_EQ(files_in_dir(), std::vector<std::string>{"replace.png"});
}

TEST(IoError, MessageIsOneLine) {
  const imageio::IoError error("a.png", "first line\nsecond line\r\n");
  EXPECT_STREQ(error.what(), "a.png: first line; second line");
  EXPECT_EQ(error.path(), "a.png");
}

}  // namespace
