// File-level PNM reading and writing; parsing lives in pnm_parse.cpp.

#include <algorithm>
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
// "P5|P6\nW H\nMAXVAL\n": the header both writers use.
std::string pnm_header(int width, int height, int channels, unsigned maxval) {
  return std::string(channels == 3 ? "P6\n" : "P5\n") + std::to_string(width) + " " + std::to_string(height) + "\n" +
         std::to_string(maxval) + "\n";
}

std::vector<std::uint8_t> encode_pnm(const Image& image) {
  const unsigned maxval = (1u << image.bits_per_sample) - 1;
  const bool wide = maxval > 255;
  const std::string header = pnm_header(image.width, image.height, image.channels, maxval);
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

void write_pnm_planes(const std::string& path, int width, int height, int bits,
                      std::span<const std::span<const std::int32_t>> planes) {
  if (planes.size() != 1 && planes.size() != 3)
    throw IoError(path, "PGM/PPM store 1 or 3 channels, the image has " + std::to_string(planes.size()));
  if (width <= 0 || height <= 0) throw IoError(path, "invalid image dimensions");
  if (bits < 1 || bits > 16) throw IoError(path, "PGM/PPM store 1 to 16 bits per sample, not " + std::to_string(bits));
  const std::size_t samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  for (const auto& plane : planes)
    if (plane.size() != samples) throw IoError(path, "a plane does not hold width x height samples");
  const auto maxval = static_cast<std::int32_t>((1u << bits) - 1);
  const bool wide = maxval > 255;
  const std::string header = pnm_header(width, height, static_cast<int>(planes.size()), static_cast<unsigned>(maxval));
  std::vector<std::uint8_t> out(header.size() + samples * planes.size() * (wide ? 2 : 1));
  std::copy(header.begin(), header.end(), out.begin());
  std::uint8_t* d = out.data() + header.size();
  for (std::size_t i = 0; i < samples; ++i)
    for (const auto& plane : planes) {
      const std::int32_t v = plane[i];
      if (v < 0 || v > maxval)
        throw IoError(path, "sample " + std::to_string(i) + " has value " + std::to_string(v) + ", outside 0.." +
                                std::to_string(maxval));
      if (wide) *d++ = static_cast<std::uint8_t>(v >> 8);  // big-endian
      *d++ = static_cast<std::uint8_t>(v & 0xFF);
    }
  detail::write_atomically(path, [&](const std::string& temporary) { detail::write_whole_file(path, temporary, out); });
}

}  // namespace imageio
