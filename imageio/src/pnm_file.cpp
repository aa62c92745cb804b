// File-level PNM reading and writing; parsing lives in pnm_parse.cpp.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "atomic_file.h"
#include "file_bytes.h"
#include "image_checks.h"
#include "imageio/plane_memory.h"
#include "imageio/pnm.h"
#include "pnm_interleave.h"

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

// The IoError for the first sample of pixels [first, first + n) outside 0..maxval.
[[noreturn]] void throw_first_outside(const std::string& path, std::span<const std::span<const std::int32_t>> planes,
                                      std::size_t first, std::size_t n, std::uint32_t maxval) {
  for (std::size_t i = first; i < first + n; ++i)
    for (const auto& plane : planes)
      if (static_cast<std::uint32_t>(plane[i]) > maxval)
        throw IoError(path, "sample " + std::to_string(i) + " has value " + std::to_string(plane[i]) + ", outside 0.." +
                                std::to_string(maxval));
  throw IoError(path, "a sample is outside 0.." + std::to_string(maxval));
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
  const auto maxval = static_cast<std::uint32_t>((1u << bits) - 1);
  const bool wide = maxval > 255;
  const std::size_t channels = planes.size(), pixel_bytes = channels * (wide ? 2 : 1);
  const std::string header = pnm_header(width, height, static_cast<int>(channels), maxval);

  // The raster is made and written a chunk at a time, each interleaved while the last is in the
  // page cache: no whole-image buffer to fault in. A sample out of range ends the write, and the
  // atomic write then leaves no file.
  constexpr std::size_t kChunkPixels = std::size_t{1} << 16;
  std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>> chunk(kChunkPixels * pixel_bytes);
  std::size_t next = 0;  // the first pixel of the next chunk
  bool header_written = false;
  auto next_chunk = [&]() -> std::span<const std::uint8_t> {
    if (!header_written) {
      header_written = true;
      return {reinterpret_cast<const std::uint8_t*>(header.data()), header.size()};
    }
    const std::size_t first = next, n = std::min(kChunkPixels, samples - next);
    if (n == 0) return {};
    next += n;
    const std::int32_t* p0 = planes[0].data() + first;
    std::uint32_t largest = 0;
    if (channels == 3) {
      const std::int32_t *p1 = planes[1].data() + first, *p2 = planes[2].data() + first;
      largest = wide ? detail::interleave_rgb16(p0, p1, p2, chunk.data(), n)
                     : detail::interleave_rgb8(p0, p1, p2, chunk.data(), n);
    } else {
      largest = wide ? detail::interleave_grey16(p0, chunk.data(), n) : detail::interleave_grey8(p0, chunk.data(), n);
    }
    if (largest > maxval) throw_first_outside(path, planes, first, n, maxval);
    return {chunk.data(), n * pixel_bytes};
  };
  detail::write_atomically(
      path, [&](const std::string& temporary) { detail::write_file_in_chunks(path, temporary, next_chunk); });
}

}  // namespace imageio
