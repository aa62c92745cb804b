// Strict Netpbm (PBM/PGM/PPM) parser. The header is validated and the image
// size checked against both the sample limit and the bytes actually present
// before pixel memory is allocated, so a hostile or corrupt header can neither
// exhaust memory nor cause reads out of bounds. This file has no dependency
// beyond the standard library so the fuzzer can compile it on its own.

#include <bit>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

#include "header_text.h"
#include "image_checks.h"
#include "imageio/plane_memory.h"
#include "imageio/pnm.h"

namespace imageio {
namespace {

using detail::is_header_space;
using detail::printable;

constexpr std::uint64_t kMaxMaxval = 65535;

bool is_digit(std::uint8_t ch) { return ch >= '0' && ch <= '9'; }

// The variants, named by the digit of their magic number.
struct Format {
  char digit = 0;
  int channels = 0;
  bool bitmap = false;  // P1/P4: no maxval, one bit per pixel
  bool plain = false;   // P1/P2/P3: ASCII raster
};

// Reads the file front to back: header fields, then the raster. Every
// access goes through pos_ < bytes_.size() checks.
class PnmReader {
 public:
  PnmReader(std::span<const std::uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& problem) const { throw IoError(name_, problem); }

  Format read_magic() {
    if (bytes_.size() < 2 || bytes_[0] != 'P' || bytes_[1] < '1' || bytes_[1] > '6') {
      fail("not a PBM/PGM/PPM file (bad magic, expected \"P1\" to \"P6\")");
    }
    Format format;
    format.digit = char(bytes_[1]);
    format.channels = (format.digit == '3' || format.digit == '6') ? 3 : 1;
    format.bitmap = format.digit == '1' || format.digit == '4';
    format.plain = format.digit <= '3';
    pos_ = 2;
    // Without this, "P5x ..." or "P52 2 ..." would be accepted.
    if (pos_ >= bytes_.size() || !(is_header_space(bytes_[pos_]) || bytes_[pos_] == '#')) {
      fail("not a PBM/PGM/PPM file (unexpected data after the magic number)");
    }
    return format;
  }

  // Reads a dimension: a positive decimal integer that fits in an int.
  int read_dimension(const char* what) {
    const std::uint64_t value = read_unsigned(what, "positive");
    if (value == 0) fail(std::string(what) + " must be positive, got 0");
    if (value > std::uint64_t(std::numeric_limits<int>::max())) fail(std::string(what) + " is too large");
    return int(value);
  }

  int read_maxval() {
    const std::uint64_t value = read_unsigned("maxval", "1..65535");
    if (value == 0 || value > kMaxMaxval) fail("maxval must be 1..65535, got " + printable(last_token_));
    return int(value);
  }

  // A raw raster starts after exactly one whitespace character following the
  // last header field, or after the line break ending a comment that
  // directly follows it (libnetpbm reads the delimiter through its comment
  // skipping). Returns the offset where the raster starts.
  std::size_t end_of_raw_header() {
    if (pos_ >= bytes_.size()) fail("truncated header (no pixel data)");
    if (bytes_[pos_] == '#') {
      skip_comment();
      if (pos_ >= bytes_.size()) fail("truncated header (no pixel data)");
    }
    // take_token stopped at whitespace or '#', and a comment ends at a line
    // break, so this is the single delimiting whitespace character.
    return pos_ + 1;
  }

  // Bytes from the current position to the end; for the plain formats'
  // size check before allocating.
  std::size_t remaining() const { return bytes_.size() - pos_; }

  // Plain raster sample: a decimal number up to maxval. Whitespace and
  // comments may precede it. `index` and `expected` only serve messages.
  std::uint32_t read_plain_sample(std::size_t index, std::uint64_t expected, int maxval) {
    skip_space_and_comments();
    if (pos_ >= bytes_.size()) fail(truncated_samples(index, expected));
    const std::string_view token = take_token();
    std::uint64_t value = 0;
    if (!parse_digits(token, value)) fail(sample_name(index) + " is not a number: \"" + printable(token) + "\"");
    if (value > std::uint64_t(maxval)) {
      fail(sample_name(index) + " is " + (value > kMaxMaxval ? printable(token) : std::to_string(value)) +
           ", above maxval " + std::to_string(maxval));
    }
    return std::uint32_t(value);
  }

  // Plain bitmap pixel: a single '0' or '1'; whitespace between them is
  // optional, so "0110" is four pixels.
  int read_plain_bit(std::size_t index, std::uint64_t expected) {
    skip_space_and_comments();
    if (pos_ >= bytes_.size()) fail(truncated_samples(index, expected));
    const std::uint8_t ch = bytes_[pos_++];
    if (ch != '0' && ch != '1') {
      fail(sample_name(index) + " is not a bitmap digit (0 or 1): \"" + printable(std::string(1, char(ch))) + "\"");
    }
    return ch - '0';
  }

  void set_sample_naming(int width, int channels) {
    width_ = width;
    channels_ = channels;
  }

  // "sample at x=3, y=0, channel 1" for messages.
  std::string sample_name(std::size_t index) const {
    const std::size_t pixel = index / std::size_t(channels_);
    std::string out = "sample at x=" + std::to_string(pixel % std::size_t(width_)) +
                      ", y=" + std::to_string(pixel / std::size_t(width_));
    if (channels_ > 1) out += ", channel " + std::to_string(index % std::size_t(channels_));
    return out;
  }

 private:
  void skip_comment() {
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
  }

  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      if (is_header_space(bytes_[pos_])) {
        ++pos_;
      } else if (bytes_[pos_] == '#') {
        skip_comment();
      } else {
        break;
      }
    }
  }

  // A token runs up to whitespace, a comment or the end of the data.
  std::string_view take_token() {
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_header_space(bytes_[pos_]) && bytes_[pos_] != '#') ++pos_;
    return {reinterpret_cast<const char*>(bytes_.data()) + start, pos_ - start};
  }

  // Decimal digits only (Netpbm has no signs). False for anything else;
  // a value too large for 64 bits is saturated, which every caller rejects.
  static bool parse_digits(std::string_view token, std::uint64_t& value) {
    if (token.empty()) return false;
    for (char ch : token) {
      if (!is_digit(std::uint8_t(ch))) return false;
    }
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec == std::errc::result_out_of_range) value = std::numeric_limits<std::uint64_t>::max();
    return true;
  }

  // `requirement` completes "WHAT must be ..." when the field is negative.
  std::uint64_t read_unsigned(const char* what, const char* requirement) {
    skip_space_and_comments();
    const std::string_view token = take_token();
    last_token_ = token;
    if (token.empty()) fail(std::string("truncated header (missing ") + what + ")");
    std::uint64_t value = 0;
    if (!parse_digits(token, value)) {
      if (token[0] == '-') {
        fail(std::string(what) + " must be " + requirement + ", got \"" + printable(token) + "\"");
      }
      fail(std::string("invalid ") + what + " \"" + printable(token) + "\"");
    }
    return value;
  }

  static std::string truncated_samples(std::size_t index, std::uint64_t expected) {
    return "truncated pixel data: expected " + std::to_string(expected) + " samples, found " + std::to_string(index);
  }

  std::span<const std::uint8_t> bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::string_view last_token_;  // the last header field read, for messages
  int width_ = 1;
  int channels_ = 1;
};

void check_size(PnmReader& reader, const Image& image, std::uint64_t samples) {
  if (samples > detail::kMaxSamples) {
    reader.fail("image too large: " + std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                std::to_string(image.channels) + (image.channels == 1 ? " channel" : " channels") +
                " exceeds the limit of " + std::to_string(detail::kMaxSamples) + " samples");
  }
}

void check_available(PnmReader& reader, std::uint64_t needed, std::uint64_t available) {
  if (available < needed) {
    reader.fail("truncated pixel data: expected " + std::to_string(needed) + " bytes, found " +
                std::to_string(available));
  }
}

// Where the samples go: interleaved floats (Image), or one integer plane per channel
// (PlanarImage, which an encoder takes without conversion). Sample index i is pixel i / channels,
// channel i % channels, in file order.
struct InterleavedSink {
  Image& image;
  void allocate(int width, int height, int channels, int bits, std::size_t samples) {
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.bits_per_sample = bits;
    image.pixels.resize(samples);
  }
  void put(std::size_t pixel, int channel, unsigned value) {
    image.pixels[pixel * std::size_t(image.channels) + std::size_t(channel)] = float(value);
  }
};

// Samples decoded into a packed raster of our own (PackedImage), for the files whose raster is
// not already one.
struct PackedSink {
  PackedImage& image;
  std::uint8_t* raster = nullptr;
  void allocate(int width, int height, int channels, int bits, std::size_t samples) {
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.bits_per_sample = bits;
    image.bytes_per_sample = bits > 8 ? 2 : 1;
    auto owned = std::make_shared<std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>>>();
    resize_with_huge_pages(*owned, samples * std::size_t(image.bytes_per_sample));
    raster = owned->data();
    image.raster = raster;
    image.storage = std::move(owned);
  }
  void put(std::size_t pixel, int channel, unsigned value) {
    const std::size_t i = pixel * std::size_t(image.channels) + std::size_t(channel);
    if (image.bytes_per_sample == 1) {
      raster[i] = std::uint8_t(value);
    } else {
      raster[2 * i] = std::uint8_t(value >> 8);
      raster[2 * i + 1] = std::uint8_t(value);
    }
  }
  // A raw raster whose samples need no check (maxval 255 or 65535) is taken where it lies.
  bool take_raster(const std::uint8_t* data, int width, int height, int channels, int maxval) {
    if (maxval != 255 && maxval != 65535) return false;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.bits_per_sample = maxval == 255 ? 8 : 16;
    image.bytes_per_sample = maxval == 255 ? 1 : 2;
    image.raster = data;
    return true;
  }
};

template <class Sink>
void read_plain(PnmReader& reader, const Format& format, int maxval, std::uint64_t samples, Sink& sink) {
  const auto channels = std::size_t(format.channels);
  for (std::size_t i = 0; i < samples; ++i) {
    const unsigned value =
        format.bitmap ? unsigned(1 - reader.read_plain_bit(i, samples)) : reader.read_plain_sample(i, samples, maxval);
    sink.put(i / channels, int(i % channels), value);
  }
}

template <class Sink>
void read_raw_bitmap(const std::uint8_t* src, int width, int height, Sink& sink) {
  const std::size_t row_bytes = (std::size_t(width) + 7) / 8;
  for (int y = 0; y < height; ++y, src += row_bytes) {
    const std::size_t row = std::size_t(y) * std::size_t(width);
    for (int x = 0; x < width; ++x) sink.put(row + std::size_t(x), 0, unsigned(1 - ((src[x / 8] >> (7 - x % 8)) & 1)));
  }
}

// `kChecked`: whether a sample can exceed maxval at all (not when maxval is 255 or 65535), so that
// the common files take a loop without the test.
template <bool kWide, bool kChecked, int kChannels, class Sink>
void read_raw_samples(PnmReader& reader, const std::uint8_t* src, int maxval, std::size_t pixels, int channels,
                      Sink& sink) {
  const int n = kChannels > 0 ? kChannels : channels;
  for (std::size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < n; ++c) {
      unsigned value = src[0];
      if constexpr (kWide) value = (value << 8) | src[1];  // big-endian
      src += kWide ? 2 : 1;
      if constexpr (kChecked)
        if (value > unsigned(maxval))
          reader.fail(reader.sample_name(p * std::size_t(n) + std::size_t(c)) + " is " + std::to_string(value) +
                      ", above maxval " + std::to_string(maxval));
      sink.put(p, c, value);
    }
}

template <class Sink>
void read_raw(PnmReader& reader, const std::uint8_t* src, int maxval, std::size_t pixels, int channels, Sink& sink) {
  const bool wide = maxval > 255;
  const bool checked = maxval != 255 && maxval != 65535;
  auto run = [&]<bool kWide, bool kChecked>() {
    if (channels == 3)
      read_raw_samples<kWide, kChecked, 3>(reader, src, maxval, pixels, channels, sink);
    else
      read_raw_samples<kWide, kChecked, 0>(reader, src, maxval, pixels, channels, sink);
  };
  if (wide)
    checked ? run.template operator()<true, true>() : run.template operator()<true, false>();
  else
    checked ? run.template operator()<false, true>() : run.template operator()<false, false>();
}

template <class Sink>
void parse_into(std::span<const std::uint8_t> bytes, const std::string& name_for_errors, Sink& sink, Image& shape) {
  PnmReader reader(bytes, name_for_errors);
  const Format format = reader.read_magic();
  shape.channels = format.channels;
  shape.width = reader.read_dimension("width");
  shape.height = reader.read_dimension("height");
  const int maxval = format.bitmap ? 1 : reader.read_maxval();
  shape.bits_per_sample = std::bit_width(unsigned(maxval));
  reader.set_sample_naming(shape.width, shape.channels);

  // Each dimension is below 2^31, so this product cannot overflow 64 bits.
  const std::uint64_t pixels = std::uint64_t(shape.width) * std::uint64_t(shape.height);
  const std::uint64_t samples = pixels * std::uint64_t(shape.channels);
  check_size(reader, shape, samples);

  if (format.plain) {
    // What is left starts with the whitespace ending the header; after it
    // each sample takes at least one character (bitmaps) or a digit and a
    // separator (the last one excepted). Checking this first keeps a tiny
    // file from making us allocate for a huge declared size.
    const std::uint64_t min_bytes = format.bitmap ? samples + 1 : 2 * samples;
    if (reader.remaining() < min_bytes) {
      reader.fail("truncated pixel data: " + std::to_string(samples) + " samples need at least " +
                  std::to_string(min_bytes) + " bytes, found " + std::to_string(reader.remaining()));
    }
    sink.allocate(shape.width, shape.height, shape.channels, shape.bits_per_sample, samples);
    read_plain(reader, format, maxval, samples, sink);
    return;
  }

  const std::size_t data_start = reader.end_of_raw_header();
  const std::uint64_t available = bytes.size() - data_start;
  const std::uint64_t needed = format.bitmap ? (std::uint64_t(shape.width) + 7) / 8 * std::uint64_t(shape.height)
                                             : samples * (maxval > 255 ? 2 : 1);
  check_available(reader, needed, available);
  // Anything after the raster is left alone: it may be the next image.
  if constexpr (requires { sink.take_raster(bytes.data(), 0, 0, 0, 0); })
    if (!format.bitmap &&
        sink.take_raster(bytes.data() + data_start, shape.width, shape.height, shape.channels, maxval))
      return;
  sink.allocate(shape.width, shape.height, shape.channels, shape.bits_per_sample, samples);
  if (format.bitmap) {
    read_raw_bitmap(bytes.data() + data_start, shape.width, shape.height, sink);
  } else {
    read_raw(reader, bytes.data() + data_start, maxval, pixels, shape.channels, sink);
  }
}

}  // namespace

Image parse_pnm(std::span<const std::uint8_t> bytes, const std::string& name_for_errors) {
  Image image;
  InterleavedSink sink{image};
  parse_into(bytes, name_for_errors, sink, image);
  return image;
}

PackedImage parse_pnm_packed(std::span<const std::uint8_t> bytes, const std::string& name_for_errors) {
  PackedImage packed;
  PackedSink sink{packed};
  Image shape;  // the header's fields, for the checks and messages
  parse_into(bytes, name_for_errors, sink, shape);
  return packed;
}

void PackedImage::unpack_row(int channel, int y, int x0, int n, std::int32_t* out) const {
  const auto step = std::size_t(channels);
  const std::uint8_t* src = raster + std::size_t(y) * row_bytes() +
                            (std::size_t(x0) * step + std::size_t(channel)) * std::size_t(bytes_per_sample);
  if (bytes_per_sample == 1) {
    if (channels == 3) {  // the common case, with a constant stride the compiler can vectorise
      for (int i = 0; i < n; ++i) out[i] = src[3 * std::size_t(i)];
      return;
    }
    for (int i = 0; i < n; ++i) out[i] = src[std::size_t(i) * step];
    return;
  }
  for (int i = 0; i < n; ++i) {
    const std::uint8_t* s = src + 2 * std::size_t(i) * step;
    out[i] = std::int32_t(s[0]) << 8 | s[1];
  }
}

}  // namespace imageio
