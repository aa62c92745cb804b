// File-level PNM reading and writing; parsing lives in pnm_parse.cpp.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
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

PnmRaster::PnmRaster(std::string path, int width, int height, int channels, int bits) : path_(std::move(path)) {
  if (channels != 1 && channels != 3)
    throw IoError(path_, "PGM/PPM store 1 or 3 channels, the image has " + std::to_string(channels));
  if (width <= 0 || height <= 0) throw IoError(path_, "invalid image dimensions");
  if (bits < 1 || bits > 16) throw IoError(path_, "PGM/PPM store 1 to 16 bits per sample, not " + std::to_string(bits));
  width_ = static_cast<std::size_t>(width);
  height_ = static_cast<std::size_t>(height);
  channels_ = static_cast<std::size_t>(channels);
  maxval_ = (1u << bits) - 1;
  sample_bytes_ = maxval_ > 255 ? 2 : 1;
  const std::string header = pnm_header(width, height, channels, maxval_);
  header_bytes_ = header.size();
  // On huge pages where the system has them: a 2048x2048 RGB raster is 3,000 ordinary pages, each
  // a fault when first touched (some 4 ms of a 0.75 bpp decode's 15 ms of setup on a 2-core VM).
  // Left uninitialised: each row is zeroed when first touched (clear_row_once).
  resize_with_huge_pages(bytes_, header_bytes_ + width_ * height_ * channels_ * sample_bytes_);
  std::copy(header.begin(), header.end(), bytes_.begin());
  row_cleared_ = std::make_unique<std::once_flag[]>(height_);
}

void PnmRaster::clear_row_once(std::size_t y) {
  std::call_once(row_cleared_[y], [&] {
    const std::size_t row_bytes = width_ * channels_ * sample_bytes_;
    std::fill_n(bytes_.data() + header_bytes_ + y * row_bytes, row_bytes, std::uint8_t{0});
  });
}

std::uint8_t* PnmRaster::pixels_at(std::size_t x, std::size_t y, std::size_t n) {
  if (y >= height_ || x > width_ || n > width_ - x)
    throw IoError(path_, "pixels [" + std::to_string(x) + ", " + std::to_string(x + n) + ") of row " +
                             std::to_string(y) + " are outside the " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " image");
  clear_row_once(y);
  return bytes_.data() + header_bytes_ + (y * width_ + x) * channels_ * sample_bytes_;
}

void PnmRaster::throw_outside(std::span<const std::int32_t> samples, std::size_t x, std::size_t y) const {
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (static_cast<std::uint32_t>(samples[i]) > maxval_)
      throw IoError(path_, "sample (" + std::to_string(x + i) + ", " + std::to_string(y) + ") has value " +
                               std::to_string(samples[i]) + ", outside 0.." + std::to_string(maxval_));
  throw IoError(path_, "a sample is outside 0.." + std::to_string(maxval_));
}

void PnmRaster::put_row(int channel, std::size_t x, std::size_t y, std::span<const std::int32_t> samples) {
  if (channel < 0 || static_cast<std::size_t>(channel) >= channels_)
    throw IoError(path_,
                  "channel " + std::to_string(channel) + " of a " + std::to_string(channels_) + "-channel image");
  std::uint8_t* out = pixels_at(x, y, samples.size());
  const std::size_t n = samples.size();
  std::uint32_t largest = 0;
  if (channels_ == 1) {
    largest = sample_bytes_ == 2 ? detail::interleave_grey16(samples.data(), out, n)
                                 : detail::interleave_grey8(samples.data(), out, n);
  } else {
    // One channel of three: every third sample, as the writer's bytes.
    out += static_cast<std::size_t>(channel) * sample_bytes_;
    const std::size_t stride = channels_ * sample_bytes_;
    for (std::size_t i = 0; i < n; ++i, out += stride) {
      const auto v = static_cast<std::uint32_t>(samples[i]);
      largest = std::max(largest, v);
      if (sample_bytes_ == 2) {
        out[0] = static_cast<std::uint8_t>(v >> 8);  // big-endian
        out[1] = static_cast<std::uint8_t>(v);
      } else {
        out[0] = static_cast<std::uint8_t>(v);
      }
    }
  }
  if (largest > maxval_) throw_outside(samples, x, y);
}

void PnmRaster::put_rgb_row(std::size_t x, std::size_t y, std::span<const std::int32_t> r,
                            std::span<const std::int32_t> g, std::span<const std::int32_t> b) {
  if (channels_ != 3) throw IoError(path_, "RGB rows put into a grey image");
  if (g.size() != r.size() || b.size() != r.size()) throw IoError(path_, "RGB rows of different lengths");
  std::uint8_t* out = pixels_at(x, y, r.size());
  const std::uint32_t largest = sample_bytes_ == 2
                                    ? detail::interleave_rgb16(r.data(), g.data(), b.data(), out, r.size())
                                    : detail::interleave_rgb8(r.data(), g.data(), b.data(), out, r.size());
  if (largest > maxval_)
    for (const auto channel : {r, g, b})
      for (const std::int32_t v : channel)
        if (static_cast<std::uint32_t>(v) > maxval_) throw_outside(channel, x, y);
}

void PnmRaster::write() {
  for (std::size_t y = 0; y < height_; ++y) clear_row_once(y);
  detail::write_atomically(path_,
                           [&](const std::string& temporary) { detail::write_whole_file(path_, temporary, bytes_); });
}

}  // namespace imageio
