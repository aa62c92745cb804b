// File-level PFM reading and writing; parsing lives in pfm_parse.cpp.

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "atomic_file.h"
#include "image_checks.h"
#include "imageio/pfm.h"

namespace imageio {
namespace {

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

std::vector<std::uint8_t> read_whole_file(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw IoError(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<std::uint8_t> bytes;
  std::uint8_t chunk[1 << 16];
  while (std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get())) {
    bytes.insert(bytes.end(), chunk, chunk + n);
  }
  if (std::ferror(file.get())) throw IoError(path, std::string("read error: ") + std::strerror(errno));
  return bytes;
}

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

void write_bytes(const std::string& path, const std::string& file_name, const std::vector<std::uint8_t>& bytes) {
  FilePtr file(std::fopen(file_name.c_str(), "wb"), &std::fclose);
  if (!file) throw IoError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
    throw IoError(path, std::string("write error: ") + std::strerror(errno));
  }
  // fclose flushes; a full disk may only show up here.
  if (std::fclose(file.release()) != 0) {
    throw IoError(path, std::string("write error: ") + std::strerror(errno));
  }
}

}  // namespace

Image read_pfm(const std::string& path) {
  const std::vector<std::uint8_t> bytes = read_whole_file(path);
  return parse_pfm(bytes, path);
}

void write_pfm(const std::string& path, const Image& image) {
  detail::check_layout(path, image);
  if (image.channels != 1 && image.channels != 3) {
    throw IoError(path, "PFM stores 1 or 3 channels, the image has " + std::to_string(image.channels));
  }
  const std::vector<std::uint8_t> bytes = encode_pfm(image);
  detail::write_atomically(path, [&](const std::string& temporary) { write_bytes(path, temporary, bytes); });
}

}  // namespace imageio
