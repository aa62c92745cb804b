// Strict PFM parser. Everything is validated before pixel memory is
// allocated, and the declared size must match the bytes present, so a
// hostile or corrupt header can neither exhaust memory nor cause reads out of
// bounds. This file has no dependency beyond the standard library so the
// fuzzer can compile it on its own.

#include <bit>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

#include "header_text.h"
#include "image_checks.h"
#include "imageio/pfm.h"

namespace imageio {
namespace {

using detail::printable;

bool is_space(std::uint8_t ch) { return detail::is_header_space(ch); }

class HeaderReader {
 public:
  HeaderReader(std::span<const std::uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& problem) const { throw IoError(name_, problem); }

  void read_magic(int& channels) {
    if (bytes_.size() < 2 || bytes_[0] != 'P' || (bytes_[1] != 'F' && bytes_[1] != 'f')) {
      fail("not a PFM file (bad magic, expected \"PF\" or \"Pf\")");
    }
    channels = bytes_[1] == 'F' ? 3 : 1;
    pos_ = 2;
    // Without this, "PFx..." or "PF5 ..." would be accepted.
    if (pos_ >= bytes_.size() || !is_space(bytes_[pos_])) {
      fail("not a PFM file (unexpected data after the magic number)");
    }
  }

  // Reads a dimension: a positive decimal integer that fits in an int.
  int read_dimension(const char* what) {
    const std::string_view token = next_token(what);
    long long value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec == std::errc::result_out_of_range) fail(std::string(what) + " is too large");
    if (ec != std::errc{} || end != token.data() + token.size()) {
      fail(std::string("invalid ") + what + " \"" + printable(token) + "\"");
    }
    if (value <= 0) fail(std::string(what) + " must be positive, got " + std::to_string(value));
    if (value > std::numeric_limits<int>::max()) fail(std::string(what) + " is too large");
    return int(value);
  }

  // Reads the scale field; only its sign matters to us (negative means
  // little-endian). Zero, NaN and infinities are invalid.
  double read_scale() {
    const std::string_view token = next_token("scale");
    double value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc{} || end != token.data() + token.size() || !std::isfinite(value) || value == 0) {
      fail("invalid scale \"" + printable(token) + "\" (must be a finite non-zero number)");
    }
    return value;
  }

  // The header ends with exactly one whitespace character after the scale;
  // pixel data starts right after it. Returns that offset.
  std::size_t end_of_header() {
    if (pos_ >= bytes_.size()) fail("truncated header (no pixel data)");
    return pos_ + 1;
  }

 private:
  std::string_view next_token(const char* what) {
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    if (start == pos_) fail(std::string("truncated header (missing ") + what + ")");
    return {reinterpret_cast<const char*>(bytes_.data()) + start, pos_ - start};
  }

  std::span<const std::uint8_t> bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

// Decodes a float from 4 bytes in the given byte order. Assembling the word
// with shifts works the same on any host, so no host-endianness test is needed.
float decode_float(const std::uint8_t* p, bool little_endian) {
  std::uint32_t word = 0;
  for (int i = 0; i < 4; ++i) word |= std::uint32_t(p[little_endian ? i : 3 - i]) << (8 * i);
  return std::bit_cast<float>(word);
}

}  // namespace

Image parse_pfm(std::span<const std::uint8_t> bytes, const std::string& name_for_errors) {
  HeaderReader header(bytes, name_for_errors);
  Image image;
  header.read_magic(image.channels);
  image.width = header.read_dimension("width");
  image.height = header.read_dimension("height");
  const bool little_endian = header.read_scale() < 0;
  const std::size_t data_start = header.end_of_header();

  // Each dimension is below 2^31, so this product cannot overflow 64 bits.
  const std::uint64_t samples =
      std::uint64_t(image.width) * std::uint64_t(image.height) * std::uint64_t(image.channels);
  if (samples > detail::kMaxSamples) {
    header.fail("image too large: " + std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                std::to_string(image.channels) + " channels exceeds the limit of " +
                std::to_string(detail::kMaxSamples) + " samples");
  }
  const std::uint64_t expected_bytes = samples * 4;
  const std::uint64_t available = bytes.size() - data_start;
  if (available < expected_bytes) {
    header.fail("truncated pixel data: expected " + std::to_string(expected_bytes) + " bytes, found " +
                std::to_string(available));
  }
  if (available > expected_bytes) {
    header.fail(std::to_string(available - expected_bytes) + " unexpected bytes after the pixel data");
  }

  image.bits_per_sample = 32;
  image.is_float = true;
  image.pixels.resize(samples);
  const std::size_t row_samples = std::size_t(image.width) * std::size_t(image.channels);
  const std::uint8_t* src = bytes.data() + data_start;
  // PFM stores the bottom row first.
  for (int file_row = 0; file_row < image.height; ++file_row) {
    float* dst = image.pixels.data() + std::size_t(image.height - 1 - file_row) * row_samples;
    for (std::size_t i = 0; i < row_samples; ++i, src += 4) {
      dst[i] = decode_float(src, little_endian);
    }
  }
  return image;
}

}  // namespace imageio
