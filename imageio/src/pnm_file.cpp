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

// The planes' samples interleaved into `out`, each in 1 byte or 2 big-endian ones (Wide), with
// no branch per sample so that the compiler vectorises the loop: the range is checked afterwards,
// against the largest sample seen as unsigned (a negative one is larger than any maxval).
template <std::size_t Channels, bool Wide>
std::uint32_t interleave(std::span<const std::span<const std::int32_t>> planes, std::size_t samples,
                         std::uint8_t* out) {
  const std::int32_t* p[Channels];
  for (std::size_t c = 0; c < Channels; ++c) p[c] = planes[c].data();
  std::uint32_t largest = 0;
  constexpr std::size_t kBytes = Wide ? 2 : 1;
  for (std::size_t i = 0; i < samples; ++i)
    for (std::size_t c = 0; c < Channels; ++c) {
      const auto v = static_cast<std::uint32_t>(p[c][i]);
      largest = std::max(largest, v);
      std::uint8_t* d = out + (i * Channels + c) * kBytes;
      if constexpr (Wide) {
        d[0] = static_cast<std::uint8_t>(v >> 8);
        d[1] = static_cast<std::uint8_t>(v);
      } else {
        d[0] = static_cast<std::uint8_t>(v);
      }
    }
  return largest;
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
  const std::string header = pnm_header(width, height, static_cast<int>(planes.size()), maxval);
  // Every byte is written below: no zeroing pass, and huge pages for the raster's first touch.
  std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>> out;
  resize_with_huge_pages(out, header.size() + samples * planes.size() * (wide ? 2 : 1));
  std::copy(header.begin(), header.end(), out.begin());
  std::uint8_t* raster = out.data() + header.size();
  std::uint32_t largest = 0;
  if (planes.size() == 3)
    largest = wide ? interleave<3, true>(planes, samples, raster) : interleave<3, false>(planes, samples, raster);
  else
    largest = wide ? interleave<1, true>(planes, samples, raster) : interleave<1, false>(planes, samples, raster);
  if (largest > maxval) {
    for (std::size_t i = 0; i < samples; ++i)
      for (const auto& plane : planes)
        if (static_cast<std::uint32_t>(plane[i]) > maxval)
          throw IoError(path, "sample " + std::to_string(i) + " has value " + std::to_string(plane[i]) +
                                  ", outside 0.." + std::to_string(maxval));
  }
  detail::write_atomically(path, [&](const std::string& temporary) {
    detail::write_whole_file(path, temporary, std::span<const std::uint8_t>(out.data(), out.size()));
  });
}

}  // namespace imageio
