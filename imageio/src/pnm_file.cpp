// File-level PNM reading and writing; parsing lives in pnm_parse.cpp.

#include <cstdint>
#include <memory>
#include <vector>

#include "atomic_file.h"
#include "file_bytes.h"
#include "image_checks.h"
#include "imageio/pnm.h"

namespace imageio {
namespace {

// Samples were checked to be integers in 0..2^bits-1, so the casts are exact.
std::vector<std::uint8_t> encode_pnm(const Image& image) {
  const unsigned maxval = (1u << image.bits_per_sample) - 1;
  const bool wide = maxval > 255;
  const std::string header = std::string(image.channels == 3 ? "P6\n" : "P5\n") + std::to_string(image.width) + " " +
                             std::to_string(image.height) + "\n" + std::to_string(maxval) + "\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.reserve(header.size() + image.pixels.size() * (wide ? 2 : 1));
  for (float sample : image.pixels) {
    const auto value = static_cast<std::uint16_t>(sample);
    if (wide) out.push_back(std::uint8_t(value >> 8));  // big-endian
    out.push_back(std::uint8_t(value & 0xff));
  }
  return out;
}

}  // namespace

Image read_pnm(const std::string& path) {
  const detail::FileBytes file(path);
  return parse_pnm(file.bytes(), path);
}

PackedImage read_pnm_packed(const std::string& path) {
  auto file = std::make_shared<const detail::FileBytes>(path);
  PackedImage image = parse_pnm_packed(file->bytes(), path);
  if (!image.storage) image.storage = std::move(file);  // the raster is the file's
  return image;
}

void write_pnm(const std::string& path, const Image& image) {
  detail::check_layout(path, image);
  if (image.channels != 1 && image.channels != 3) {
    throw IoError(path, "PGM/PPM store 1 or 3 channels, the image has " + std::to_string(image.channels));
  }
  if (image.is_float) throw IoError(path, "PGM/PPM cannot store float samples");
  if (image.is_signed) throw IoError(path, "PGM/PPM cannot store signed samples");
  detail::check_integer_samples(path, image);
  const std::vector<std::uint8_t> bytes = encode_pnm(image);
  detail::write_atomically(path,
                           [&](const std::string& temporary) { detail::write_whole_file(path, temporary, bytes); });
}

}  // namespace imageio
