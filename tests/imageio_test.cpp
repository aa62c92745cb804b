// Tests for imageio: exact PFM, PNM and OpenImageIO round trips, strict PFM and
// PNM header validation, one-line "PATH: problem" errors and atomic writes.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <tuple>
#include <vector>

#include <unistd.h>

#include "imageio/image.h"
#include "imageio/pfm.h"
#include "imageio/plane_memory.h"
#include "imageio/pnm.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "support/jp2_boxes.h"

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

// ---------------------------------------------------------------- PNM

// Integer image for PNM tests: the full sweep of integer_image plus the
// values where 8-bit, 16-bit and byte-order mistakes show (0, 1, 255, 256,
// 65535 for 16 bits).
imageio::Image pnm_image(int width, int height, int channels, int bits) {
  imageio::Image image = integer_image(width, height, channels, bits, false);
  const float top = float((1 << bits) - 1);
  const std::vector<float> markers = {0, top, 1, 255, 256, 65535, 258};
  for (std::size_t i = 0; i < markers.size() && i < image.pixels.size(); ++i) {
    if (markers[i] <= top) image.pixels[i] = markers[i];
  }
  return image;
}

std::string bytes_of(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

std::string pnm_header(const std::string& magic, int width, int height, int maxval) {
  return magic + "\n" + std::to_string(width) + " " + std::to_string(height) + "\n" + std::to_string(maxval) + "\n";
}

TEST_F(ImageIoTest, PnmRoundTripIsExact) {
  for (const int bits : {8, 16}) {
    for (const auto& [name, channels] : std::vector<std::pair<std::string, int>>{{"grey.pgm", 1}, {"colour.ppm", 3}}) {
      SCOPED_TRACE(std::to_string(bits) + "-bit " + name);
      const imageio::Image original = pnm_image(9, 5, channels, bits);
      const std::string file = path(name);
      imageio::write_image(file, original);
      const std::vector<std::uint8_t> bytes = read_bytes(file);
      const std::string header = pnm_header(channels == 1 ? "P5" : "P6", 9, 5, (1 << bits) - 1);
      ASSERT_EQ(bytes.size(), header.size() + original.pixels.size() * (bits == 8 ? 1 : 2));
      EXPECT_EQ(bytes_of(bytes).substr(0, header.size()), header);

      const imageio::Image back = imageio::read_image(file);
      EXPECT_EQ(back.bits_per_sample, bits);
      EXPECT_FALSE(back.is_signed);
      EXPECT_FALSE(back.is_float);
      expect_same_pixels(original, back);
      expect_same_pixels(original, imageio::read_pnm(file));

      imageio::write_pnm(file, original);
      EXPECT_EQ(read_bytes(file), bytes);
    }
  }
  EXPECT_EQ(files_in_dir().size(), 2u);
}

// PnmRaster (a decoder's rows, in any order) writes the bytes write_pnm writes for the same
// samples, for 1 and 3 channels of 8, 12 and 16 bits, rows put a channel at a time or (RGB) all
// three at once, in pieces and out of order; a sample outside 0..maxval, negative or too large, is
// an IoError naming it, and no file is written; rows never put are zeros; a row outside the
// raster is an IoError.
TEST_F(ImageIoTest, PnmRasterWritesWhatWritePnmWrites) {
  constexpr int kWidth = 37, kHeight = 5;
  for (const int bits : {8, 12, 16})
    for (const int channels : {1, 3})
      for (const bool rgb_rows : {false, true}) {
        if (rgb_rows && channels != 3) continue;
        SCOPED_TRACE(std::to_string(bits) + " bits, " + std::to_string(channels) + " channels" +
                     (rgb_rows ? ", RGB rows" : ""));
        const imageio::Image original = pnm_image(kWidth, kHeight, channels, bits);
        std::vector<std::vector<std::int32_t>> planes(static_cast<std::size_t>(channels));
        for (std::size_t i = 0; i < original.pixels.size(); ++i)
          planes[i % static_cast<std::size_t>(channels)].push_back(static_cast<std::int32_t>(original.pixels[i]));
        // Row y, pixels [x, x + n) of every channel.
        auto put = [&](imageio::PnmRaster& raster, std::size_t x, std::size_t y, std::size_t n) {
          auto piece = [&](std::size_t c) {
            return std::span<const std::int32_t>(planes[c].data() + y * kWidth + x, n);
          };
          if (rgb_rows) return raster.put_rgb_row(x, y, piece(0), piece(1), piece(2));
          for (std::size_t c = planes.size(); c-- > 0;) raster.put_row(static_cast<int>(c), x, y, piece(c));
        };
        imageio::write_pnm(path("whole.pnm"), original);
        imageio::PnmRaster raster(path("raster.pnm"), kWidth, kHeight, channels, bits);
        for (const std::size_t y : {3, 0, 4, 1, 2}) {
          put(raster, 20, y, kWidth - 20);
          put(raster, 0, y, 20);
        }
        raster.write();
        EXPECT_EQ(read_bytes(path("raster.pnm")), read_bytes(path("whole.pnm")));

        for (const std::int32_t bad : {-1, (1 << bits)}) {
          planes.back()[2 * kWidth + 26] = bad;
          const std::string file = path("bad.pnm");
          const std::string message = expect_io_error(file, [&] {
            imageio::PnmRaster bad_raster(file, kWidth, kHeight, channels, bits);
            for (std::size_t y = 0; y < kHeight; ++y) put(bad_raster, 0, y, kWidth);
            bad_raster.write();
          });
          EXPECT_NE(message.find("sample (26, 2) has value " + std::to_string(bad)), std::string::npos) << message;
          EXPECT_FALSE(std::filesystem::exists(file));
          planes.back()[2 * kWidth + 26] = 0;
        }
      }

  // Row 0 never put, row 1 in full, row 2 only its last two pixels: the rest is 0, also where the
  // raster's memory was used before (a freed block of its size is what malloc hands out next).
  const std::string unput_path = path("unput.pgm");
  { const std::vector<std::uint8_t> dirty(pnm_header("P5", 3, 3, 255).size() + 9, 0xAB); }
  imageio::PnmRaster unput(unput_path, 3, 3, 1, 8);
  const std::vector<std::int32_t> row{7, 8, 9};
  unput.put_row(0, 0, 1, row);
  unput.put_row(0, 1, 2, std::span(row).first(2));
  EXPECT_THROW(unput.put_row(0, 1, 1, row), imageio::IoError);  // pixels 1..3 of a 3-pixel row
  EXPECT_THROW(unput.put_row(0, 0, 3, row), imageio::IoError);  // row 3 of 3
  EXPECT_THROW(unput.put_row(1, 0, 0, row), imageio::IoError);  // channel 1 of a grey image
  unput.write();
  EXPECT_EQ(bytes_of(read_bytes(path("unput.pgm"))),
            pnm_header("P5", 3, 3, 255) + std::string("\0\0\0\x07\x08\x09\0\x07\x08", 9));
}

TEST_F(ImageIoTest, Pnm16BitSamplesAreBigEndian) {
  imageio::Image image = make_image(4, 1, 1, 16, false);
  image.pixels = {1, 256, 65535, 0x1234};
  const std::string file = path("order.pgm");
  imageio::write_image(file, image);
  EXPECT_EQ(bytes_of(read_bytes(file)),
            pnm_header("P5", 4, 1, 65535) + std::string("\x00\x01\x01\x00\xff\xff\x12\x34", 8));
}

TEST_F(ImageIoTest, PnmKeepsOtherBitDepths) {
  for (const int bits : {1, 2, 7, 9, 12, 15}) {
    SCOPED_TRACE(bits);
    const imageio::Image original = pnm_image(6, 4, bits % 2 ? 1 : 3, bits);
    const std::string file = path("depth.pnm");
    imageio::write_image(file, original);
    const std::string header = pnm_header(original.channels == 1 ? "P5" : "P6", 6, 4, (1 << bits) - 1);
    EXPECT_EQ(bytes_of(read_bytes(file)).substr(0, header.size()), header);
    const imageio::Image back = imageio::read_image(file);
    EXPECT_EQ(back.bits_per_sample, bits);
    expect_same_pixels(original, back);
  }
}

TEST_F(ImageIoTest, Pnm12BitMaxval) {
  // maxval 4095 takes two bytes per sample; 4095 is 0f ff, 2048 is 08 00.
  const std::string file = path("twelve.pgm");
  write_bytes(file, pnm_header("P5", 3, 1, 4095) + std::string("\x0f\xff\x00\x00\x08\x00", 6));
  const imageio::Image image = imageio::read_image(file);
  EXPECT_EQ(image.bits_per_sample, 12);
  EXPECT_EQ(image.pixels, (std::vector<float>{4095, 0, 2048}));

  write_bytes(file, pnm_header("P5", 3, 1, 4095) + std::string("\x0f\xff\x10\x00\x08\x00", 6));
  EXPECT_NE(expect_io_error(file, [&] { imageio::read_image(file); }).find("above maxval 4095"), std::string::npos);
}

TEST_F(ImageIoTest, PnmMaxvalThatIsNotAPowerOfTwoMinusOne) {
  // Samples keep their values; bits_per_sample is what maxval needs.
  const std::string file = path("odd.pgm");
  write_bytes(file, pnm_header("P5", 2, 1, 1000) + std::string("\x03\xe8\x00\x07", 4));
  imageio::Image image = imageio::read_image(file);
  EXPECT_EQ(image.bits_per_sample, 10);
  EXPECT_EQ(image.pixels, (std::vector<float>{1000, 7}));

  write_bytes(file, pnm_header("P5", 2, 1, 100) + std::string("\x64\x00", 2));
  image = imageio::read_image(file);
  EXPECT_EQ(image.bits_per_sample, 7);
  EXPECT_EQ(image.pixels, (std::vector<float>{100, 0}));

  // Written back, the file states the full range of those bits.
  imageio::write_image(file, image);
  EXPECT_EQ(bytes_of(read_bytes(file)), pnm_header("P5", 2, 1, 127) + std::string("\x64\x00", 2));
}

TEST_F(ImageIoTest, PlainPnmWithComments) {
  const std::string grey = path("plain.pgm");
  write_bytes(grey,
              "P2# comment right after the magic\n"
              "# a full-line comment\n"
              "3#comment after the width\n"
              "\t 2\r\n"
              "# between height and maxval\n"
              "65535 # after maxval\n"
              "0 1 65535\n"
              "256\t255 # inside the raster, as libnetpbm allows\n"
              "00012\n");
  imageio::Image image = imageio::read_image(grey);
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.channels, 1);
  EXPECT_EQ(image.bits_per_sample, 16);
  EXPECT_EQ(image.pixels, (std::vector<float>{0, 1, 65535, 256, 255, 12}));

  const std::string rgb = path("plain.ppm");
  write_bytes(rgb, "P3\n# RGB\n2 1 # size\n255\n255 0 1\n# second pixel\n2 3 4");
  image = imageio::read_image(rgb);
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.bits_per_sample, 8);
  EXPECT_EQ(image.pixels, (std::vector<float>{255, 0, 1, 2, 3, 4}));
}

TEST_F(ImageIoTest, RawPnmHeaderComments) {
  // A comment directly after maxval ends the header with its line break.
  const std::string file = path("comment.ppm");
  write_bytes(file, "P6 #c\n1#c\n1\n#c\n255#c\n\x01\x02\x0a");
  const imageio::Image image = imageio::read_image(file);
  EXPECT_EQ(image.pixels, (std::vector<float>{1, 2, 10}));
}

TEST_F(ImageIoTest, PnmBitmaps) {
  // 10x2 with 1 = black; each P4 row takes 2 bytes, the last 6 bits of which
  // are padding (set here, and ignored).
  const std::vector<int> bits = {1, 0, 0, 0, 0, 0, 0, 1, 1, 0,  //
                                 0, 1, 1, 1, 1, 1, 1, 0, 0, 1};
  std::vector<float> expected;
  for (int bit : bits) expected.push_back(float(1 - bit));

  const std::string raw = path("raw.pbm");
  write_bytes(raw, "P4\n# bitmap\n10 2\n" + std::string("\x81\xbf\x7e\x7f", 4));
  imageio::Image image = imageio::read_image(raw);
  EXPECT_EQ(image.width, 10);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.channels, 1);
  EXPECT_EQ(image.bits_per_sample, 1);
  EXPECT_EQ(image.pixels, expected);

  // Plain bitmaps may run the bits together or separate them.
  const std::string plain = path("plain.pbm");
  write_bytes(plain, "P1\n10 2\n1000000110\n0 1 1 1 1 1 1 0 0 # end\n1\n");
  image = imageio::read_image(plain);
  EXPECT_EQ(image.bits_per_sample, 1);
  EXPECT_EQ(image.pixels, expected);

  // A 1-bit image is written as a PGM with maxval 1 and reads back the same.
  imageio::write_image(plain, image);
  std::string samples;
  for (float v : expected) samples += char(v);
  EXPECT_EQ(bytes_of(read_bytes(plain)), pnm_header("P5", 10, 2, 1) + samples);
  expect_same_pixels(image, imageio::read_image(plain));
}

TEST_F(ImageIoTest, PnmReadsOnlyTheFirstImage) {
  const std::string file = path("two.pgm");
  write_bytes(file, pnm_header("P5", 2, 1, 255) + "\x05\x06" + pnm_header("P5", 1, 1, 255) + "\x07");
  EXPECT_EQ(imageio::read_image(file).pixels, (std::vector<float>{5, 6}));
  write_bytes(file, "P2 2 1 255 5 6 whatever follows");
  EXPECT_EQ(imageio::read_image(file).pixels, (std::vector<float>{5, 6}));
}

TEST_F(ImageIoTest, PnmExtensionIsCaseInsensitive) {
  for (const std::string name : {"a.PGM", "b.Ppm", "c.pNm", "d.PBM"}) {
    SCOPED_TRACE(name);
    const imageio::Image original = pnm_image(3, 2, 1, 16);
    const std::string file = path(name);
    imageio::write_image(file, original);
    EXPECT_EQ(bytes_of(read_bytes(file)).substr(0, 3), "P5\n");
    expect_same_pixels(original, imageio::read_image(file));
  }
}

TEST_F(ImageIoTest, PnmUnderAnotherExtensionIsReadExactly) {
  // OpenImageIO recognises the content; our reader then takes over, so the
  // 16-bit samples are not rescaled.
  const std::string file = path("sixteen.img");
  write_bytes(file, pnm_header("P5", 3, 1, 65535) + std::string("\xff\xff\x00\x01\xff\xfe", 6));
  const imageio::Image image = imageio::read_image(file);
  EXPECT_EQ(image.bits_per_sample, 16);
  EXPECT_EQ(image.pixels, (std::vector<float>{65535, 1, 65534}));
}

TEST_F(ImageIoTest, MalformedPnmIsRejected) {
  const std::string raw4 = "\x01\x02\x03\x04";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty", ""},
      {"only_p", "P"},
      {"bad_magic_pam", "P7\n2 2\n255\n" + raw4},
      {"bad_magic_zero", "P0\n2 2\n255\n" + raw4},
      {"bad_magic_pfm", "Pf\n2 2\n-1.0\n" + raw4},
      {"bad_magic_lower", "p5\n2 2\n255\n" + raw4},
      {"garbage_after_magic", "P5x\n2 2\n255\n" + raw4},
      {"digit_after_magic", "P52 2\n255\n" + raw4},
      {"missing_width", "P5\n"},
      {"missing_height", "P5\n2"},
      {"missing_height_comment", "P5\n2 # 2 255\n"},
      {"missing_maxval", "P5\n2 2"},
      {"zero_width", "P5\n0 2\n255\n" + raw4},
      {"zero_height", "P2\n2 0\n255\n1 2 3 4"},
      {"negative_width", "P5\n-2 2\n255\n" + raw4},
      {"negative_height", "P6\n2 -2\n255\n" + raw4},
      {"plus_width", "P5\n+2 2\n255\n" + raw4},
      {"non_numeric_width", "P5\nabc 2\n255\n" + raw4},
      {"width_with_junk", "P5\n2x 2\n255\n" + raw4},
      {"width_overflow", "P5\n99999999999999999999999 2\n255\n" + raw4},
      {"width_above_int", "P5\n2147483648 1\n255\n" + raw4},
      {"huge_dimensions", "P6\n100000000 100000000\n255\n" + raw4},
      {"too_many_samples", "P5\n65536 32769\n255\n" + raw4},
      {"too_many_rgb_samples", "P6\n32768 21846\n255\n" + raw4},
      {"too_many_bits", "P4\n65536 32769\n" + raw4},
      {"plain_huge_for_its_size", "P2\n40000 40000\n255\n1 2 3 4"},
      {"plain_bitmap_huge_for_its_size", "P1\n40000 40000\n0101"},
      {"maxval_zero", "P5\n2 2\n0\n" + raw4},
      {"maxval_too_large", "P5\n2 2\n65536\n" + raw4 + raw4},
      {"maxval_negative", "P5\n2 2\n-1\n" + raw4},
      {"maxval_text", "P5\n2 2\nff\n" + raw4},
      {"header_only", "P5\n2 2\n255"},
      {"header_comment_only", "P5\n2 2\n255#"},
      {"no_data", "P5\n2 2\n255\n"},
      {"truncated_data", "P5\n2 2\n255\n" + raw4.substr(0, 3)},
      {"truncated_rgb", "P6\n2 2\n255\n" + raw4 + raw4},
      {"truncated_16bit", "P5\n2 2\n65535\n" + raw4 + raw4.substr(0, 3)},
      {"truncated_bitmap", "P4\n9 2\n" + raw4.substr(0, 3)},
      {"raw_sample_above_maxval", "P5\n2 2\n100\n\x01\x65\x02\x03"},
      {"raw_16bit_above_maxval", "P5\n1 1\n1000\n\x03\xe9"},
      {"plain_sample_above_maxval", "P2\n2 2\n15\n1 2 16 4"},
      {"plain_sample_huge", "P2\n2 2\n15\n1 2 99999999999999999999999 4"},
      {"plain_sample_negative", "P2\n2 2\n15\n1 2 -3 4"},
      {"plain_sample_junk", "P3\n1 1\n255\n1 2x 3"},
      {"plain_truncated", "P2\n3 2\n255\n1 2 3 4 5"},
      {"plain_truncated_comment", "P2\n2 2\n255\n1 2 3 # 4"},
      {"plain_rgb_truncated", "P3\n2 1\n255\n1 2 3 4 5"},
      {"plain_bitmap_bad_digit", "P1\n2 2\n0 1 2 0"},
      {"plain_bitmap_truncated", "P1\n3 2\n01010"},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const std::string file = path(name + ".pgm");
    write_bytes(file, bytes);
    expect_io_error(file, [&] { imageio::read_pnm(file); });
    expect_io_error(file, [&] { imageio::read_image(file); });
    // The parser itself, as the fuzzer calls it.
    const std::vector<std::uint8_t> raw(bytes.begin(), bytes.end());
    expect_io_error("mem", [&] { imageio::parse_pnm(raw, "mem"); });
  }
}

TEST_F(ImageIoTest, PnmErrorsSayWhatIsWrong) {
  const std::string file = path("bad.pgm");
  const auto message_for = [&](const std::string& bytes) {
    write_bytes(file, bytes);
    return expect_io_error(file, [&] { imageio::read_image(file); });
  };
  EXPECT_EQ(message_for("P7\n"), file + ": not a PBM/PGM/PPM file (bad magic, expected \"P1\" to \"P6\")");
  EXPECT_EQ(message_for("P5\n-3 2\n255\n"), file + ": width must be positive, got \"-3\"");
  EXPECT_EQ(message_for("P5\n3 0\n255\n"), file + ": height must be positive, got 0");
  EXPECT_EQ(message_for("P5\n3 2\n70000\n"), file + ": maxval must be 1..65535, got 70000");
  EXPECT_EQ(message_for("P5\n3 2\n255\n\x01"), file + ": truncated pixel data: expected 6 bytes, found 1");
  EXPECT_EQ(message_for("P2\n3 2\n255\n1 2 3 4 5 # six?\n"),
            file + ": truncated pixel data: expected 6 samples, found 5");
  EXPECT_EQ(message_for("P2\n3 2\n255\n1 2 3 4 5"),
            file + ": truncated pixel data: 6 samples need at least 12 bytes, found 10");
  EXPECT_EQ(message_for("P6\n2 1\n200\n\x01\x02\x03\x04\xc9\x06"),
            file + ": sample at x=1, y=0, channel 1 is 201, above maxval 200");
  EXPECT_NE(message_for("P5\n100000 100000\n255\n").find("too large"), std::string::npos);
  EXPECT_NE(message_for("P2\n40000 40000\n255\n1").find("truncated"), std::string::npos);
}

TEST_F(ImageIoTest, ReadGreyscaleRejectsPpm) {
  const std::string rgb = path("rgb.ppm");
  imageio::write_image(rgb, pnm_image(4, 4, 3, 16));
  EXPECT_EQ(expect_io_error(rgb, [&] { imageio::read_greyscale(rgb); }),
            rgb + ": expected a greyscale image, found 3 channels");
  const std::string grey = path("grey.pgm");
  imageio::write_image(grey, pnm_image(4, 4, 1, 16));
  EXPECT_EQ(imageio::read_greyscale(grey).bits_per_sample, 16);
}

TEST_F(ImageIoTest, PnmWriteRejectsWhatItCannotStore) {
  imageio::Image out_of_range = pnm_image(3, 3, 1, 12);
  out_of_range.pixels[4] = 4096;
  imageio::Image fraction = pnm_image(3, 3, 3, 8);
  fraction.pixels[2] = 1.5f;
  imageio::Image too_deep = pnm_image(3, 3, 1, 16);
  too_deep.bits_per_sample = 17;
  imageio::Image wrong_size = pnm_image(3, 3, 1, 8);
  wrong_size.pixels.pop_back();
  const std::vector<imageio::Image> images = {pnm_image(3, 3, 2, 8),
                                              pnm_image(3, 3, 4, 16),
                                              integer_image(3, 3, 1, 8, true),
                                              float_image(3, 3, 1),
                                              out_of_range,
                                              fraction,
                                              too_deep,
                                              wrong_size};
  for (std::size_t i = 0; i < images.size(); ++i) {
    SCOPED_TRACE(i);
    for (const std::string name : {"bad.pgm", "bad.ppm"}) {
      const std::string file = path(name);
      expect_io_error(file, [&] { imageio::write_image(file, images[i]); });
      expect_io_error(file, [&] { imageio::write_pnm(file, images[i]); });
    }
  }
  EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIoTest, PnmWriteIsAtomic) {
  const std::string file = path("keep.pgm");
  write_bytes(file, "previous contents");
  expect_io_error(file, [&] { imageio::write_image(file, integer_image(4, 4, 1, 16, true)); });
  EXPECT_EQ(bytes_of(read_bytes(file)), "previous contents");
  EXPECT_EQ(files_in_dir(), std::vector<std::string>{"keep.pgm"});

  const imageio::Image image = pnm_image(4, 4, 1, 16);
  imageio::write_image(file, image);
  expect_same_pixels(image, imageio::read_image(file));
  EXPECT_EQ(files_in_dir(), std::vector<std::string>{"keep.pgm"});

  const std::string missing = path("no/such/dir/out.ppm");
  expect_io_error(missing, [&] { imageio::write_image(missing, pnm_image(2, 2, 3, 8)); });
  EXPECT_EQ(files_in_dir(), std::vector<std::string>{"keep.pgm"});
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
  for (const std::string name : {"missing.png", "missing.pfm", "missing.tif", "missing.pgm"}) {
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

// The packed reader gives read_pnm's samples for every kind of PNM, unpacked from any column;
// a raw raster with maxval 255 or 65535 is the file's own bytes, not a copy.
TEST_F(ImageIoTest, PackedPnmHasTheSamplesOfEveryKind) {
  struct Case {
    std::string name, bytes;
    bool raster_in_file;
  };
  const std::string raw8 = std::string("P6\n3 2\n255\n") +
                           std::string("\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0a\x0b\x0c\xfd\xfe\xff\x00\x80\x7f", 18);
  const std::string raw16 = std::string("P5\n2 2\n65535\n") + std::string("\x01\x02\xff\xfe\x00\x00\x80\x01", 8);
  const Case cases[] = {
      {"raw8.ppm", raw8, true},
      {"raw16.pgm", raw16, true},
      {"plain.ppm", "P3\n2 2\n1000\n1 2 3 999 5 6\n7 8 9 10 11 1000\n", false},
      {"odd_maxval.pgm", std::string("P5 3 1 100 ") + std::string("\x00\x32\x64", 3), false},
      {"bitmap.pbm", std::string("P4\n9 2\n") + std::string("\xa5\x80\x0f\x00", 4), false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    write_bytes(path(c.name), c.bytes);
    const imageio::Image expected = imageio::read_pnm(path(c.name));
    const std::vector<std::uint8_t> bytes = read_bytes(path(c.name));
    const imageio::PackedImage parsed = imageio::parse_pnm_packed(bytes, c.name);
    const bool points_into_bytes = parsed.raster >= bytes.data() && parsed.raster < bytes.data() + bytes.size();
    EXPECT_EQ(points_into_bytes, c.raster_in_file);
    const std::optional<imageio::PackedImage> read = imageio::read_packed_if_native(path(c.name));
    ASSERT_TRUE(read.has_value());
    for (const imageio::PackedImage* packed : {&parsed, &*read}) {
      ASSERT_EQ(packed->width, expected.width);
      ASSERT_EQ(packed->height, expected.height);
      ASSERT_EQ(packed->channels, expected.channels);
      EXPECT_EQ(packed->bits_per_sample, expected.bits_per_sample);
      for (int y = 0; y < expected.height; ++y)
        for (int ch = 0; ch < expected.channels; ++ch)
          for (int x0 = 0; x0 < expected.width; ++x0) {
            std::vector<std::int32_t> row(std::size_t(expected.width - x0), -1);
            packed->unpack_row(ch, y, x0, expected.width - x0, row.data());
            for (int x = x0; x < expected.width; ++x)
              ASSERT_EQ(float(row[std::size_t(x - x0)]), expected.at(x, y, ch)) << x << "," << y << " channel " << ch;
          }
    }
  }
  EXPECT_FALSE(imageio::read_packed_if_native(path("image.png")).has_value());  // not ours: no attempt
  write_bytes(path("bad.ppm"), "P6\n3 2\n255\n\x01");
  EXPECT_THROW(imageio::read_packed_if_native(path("bad.ppm")), imageio::IoError);  // truncated
}

TEST(IoError, MessageIsOneLine) {
  const imageio::IoError error("a.png", "first line\nsecond line\r\n");
  EXPECT_STREQ(error.what(), "a.png: first line; second line");
  EXPECT_EQ(error.path(), "a.png");
}

}  // namespace

// An ICC profile travels through the formats that can carry one (j2kdec hands a JP2 file's on).
// A resolution set on an image is written and read back in pixels per metre, across and down
// apart (non-square pixels): TIFF keeps it as a float per centimetre, PNG as whole pixels per metre,
// JPEG (JFIF) as whole dots per centimetre. PNM has no place for one.
TEST_F(ImageIoTest, ResolutionRoundTripsThroughTiffPngAndJpeg) {
  imageio::Image image = make_image(5, 3, 3, 8, false);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<float>((i * 37) % 256);
  image.x_pixels_per_metre = 3780;
  image.y_pixels_per_metre = 2000;
  for (const auto& [name, tolerance] :
       {std::pair<std::string, double>{"res.tif", 0.01}, {"res.png", 1.0}, {"res.jpg", 100.0}}) {
    SCOPED_TRACE(name);
    imageio::write_image(path(name), image);
    const imageio::Image back = imageio::read_image(path(name));
    EXPECT_NEAR(back.x_pixels_per_metre, 3780, tolerance);
    EXPECT_NEAR(back.y_pixels_per_metre, 2000, tolerance);
  }
  imageio::write_image(path("res.ppm"), image);
  EXPECT_EQ(imageio::read_image(path("res.ppm")).x_pixels_per_metre, 0);
  image.x_pixels_per_metre = image.y_pixels_per_metre = 0;
  imageio::write_image(path("none.png"), image);
  EXPECT_EQ(imageio::read_image(path("none.png")).x_pixels_per_metre, 0);
}

TEST_F(ImageIoTest, IccProfileRoundTripsThroughTiffAndPng) {
  imageio::Image image = make_image(5, 3, 3, 8, false);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<float>((i * 37) % 256);
  image.icc_profile = test_support::made_up_icc_profile(500);
  for (const std::string name : {"icc.tif", "icc.png"}) {
    SCOPED_TRACE(name);
    imageio::write_image(path(name), image);
    const imageio::Image back = imageio::read_image(path(name));
    EXPECT_EQ(back.icc_profile, image.icc_profile);
    EXPECT_EQ(back.pixels, image.pixels);
  }
  image.icc_profile.clear();
  imageio::write_image(path("none.tif"), image);
  EXPECT_TRUE(imageio::read_image(path("none.tif")).icc_profile.empty());
}

// discard_pages drops exactly the whole pages inside its range: they read as zeros, while the
// partial pages at either end (shared with data outside the range) keep their values; memory
// populated for writing is writable as it was.
TEST(PlaneMemory, DiscardPagesZeroesOnlyTheWholePagesInside) {
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  std::vector<std::uint8_t, imageio::UninitialisedAllocator<std::uint8_t>> bytes;
  imageio::resize_with_huge_pages(bytes, 8 * page);
  imageio::populate_for_writing(bytes.data(), bytes.size());  // where supported: the pages exist before the fill
  std::fill(bytes.begin(), bytes.end(), std::uint8_t{7});
  // From the middle of page 1 (of the allocation, which need not start on a page) to the middle of page 5.
  const std::size_t from = page + page / 2, to = 5 * page + page / 2;
  imageio::discard_pages(bytes.data() + from, to - from);
  const auto base = reinterpret_cast<std::uintptr_t>(bytes.data());
  std::size_t zeroed = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const std::uintptr_t at = base + i;
    const bool whole_page_inside = at >= (base + from + page - 1) / page * page && at < (base + to) / page * page;
    if (whole_page_inside) {
      ++zeroed;
      ASSERT_EQ(bytes[i], 0) << "byte " << i;
    } else {
      ASSERT_EQ(bytes[i], 7) << "byte " << i;
    }
  }
  EXPECT_GE(zeroed, 3 * page);
  imageio::discard_pages(nullptr, page);               // nothing to do
  imageio::discard_pages(bytes.data() + 1, page / 2);  // no whole page: nothing
  EXPECT_EQ(bytes[1], 7);
}
