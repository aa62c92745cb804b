// File-level PFM reading and writing; parsing lives in pfm_parse.cpp.

#include <bit>
#include <cstdint>
#include <vector>

#include "atomic_file.h"
#include "file_bytes.h"
#include "image_checks.h"
#include "imageio/pfm.h"

namespace imageio {
namespace {

void append_le(std::vector<std::uint8_t>& out, float value) {
  const std::uint32_t word = std::bit_cast<std::uint32_t>(value);
  for (int shift = 0; shift < 32; shift += 8) out.push_back(std::uint8_t(word >> shift));
}

std::vector<std::uint8_t> encode_pfm(const Image& image) {
  const std::string header = std::string(image.channels == 3 ? "PF\n" : "Pf\n") + std::to_string(image.width) + " " +
                             std::to_string(image.height) + "\n-1.0\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.reserve(header.size() + image.pixels.size() * 4);
  const std::size_t row_samples = std::size_t(image.width) * std::size_t(image.channels);
  // PFM stores the bottom row first.
  for (int y = image.height - 1; y >= 0; --y) {
    const float* row = image.pixels.data() + std::size_t(y) * row_samples;
    for (std::size_t i = 0; i < row_samples; ++i) append_le(out, row[i]);
  }
  return out;
}

}  // namespace

Image read_pfm(const std::string& path) {
  const detail::FileBytes file(path);
  return parse_pfm(file.bytes(), path);
}

void write_pfm(const std::string& path, const Image& image) {
  detail::check_layout(path, image);
  if (image.channels != 1 && image.channels != 3) {
    throw IoError(path, "PFM stores 1 or 3 channels, the image has " + std::to_string(image.channels));
  }
  const std::vector<std::uint8_t> bytes = encode_pfm(image);
  detail::write_atomically(path,
                           [&](const std::string& temporary) { detail::write_whole_file(path, temporary, bytes); });
}

}  // namespace imageio
