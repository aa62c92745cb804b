#include "codec/encoder/source_image.h"

#include <algorithm>
#include <cmath>

#include "codec/structure/error.h"
#include "imageio/image.h"
#include "imageio/plane_memory.h"

namespace codec {

namespace {

void check_shape(int width, int height, int channels, int bits, const std::string& path) {
  if (bits < 1 || bits > 16)
    throw EncodeError(path + ": unsupported sample precision of " + std::to_string(bits) + " bits");
  if (channels < 1 || channels > 16384)
    throw EncodeError(path + ": unsupported number of components (" + std::to_string(channels) + ")");
  if (width <= 0 || height <= 0) throw EncodeError(path + ": the image is empty");
}

}  // namespace

SourceImage to_source_image(imageio::PackedImage&& image, const std::string& path) {
  check_shape(image.width, image.height, image.channels, image.bits_per_sample, path);
  if (image.raster == nullptr || (image.bytes_per_sample != 1 && image.bytes_per_sample != 2) ||
      image.bits_per_sample > 8 * image.bytes_per_sample)
    throw EncodeError(path + ": " + std::to_string(image.bits_per_sample) + "-bit samples packed in " +
                      std::to_string(image.bytes_per_sample) + " bytes");
  SourceImage out;
  out.width = image.width;
  out.height = image.height;
  for (int c = 0; c < image.channels; ++c) {
    SourceComponent comp;
    comp.precision = image.bits_per_sample;
    out.components.push_back(std::move(comp));
  }
  out.packed = std::make_shared<const imageio::PackedImage>(std::move(image));
  return out;
}

const std::int32_t* source_row(const SourceImage& image, std::size_t c, std::size_t y, std::size_t x0, std::size_t n,
                               std::int32_t* scratch) {
  if (!image.packed) return image.components[c].samples.data() + y * static_cast<std::size_t>(image.width) + x0;
  image.packed->unpack_row(static_cast<int>(c), static_cast<int>(y), static_cast<int>(x0), static_cast<int>(n),
                           scratch);
  return scratch;
}

SourceImage to_source_image(const imageio::Image& image, const std::string& path) {
  if (image.is_float)
    throw EncodeError(path + ": floating-point samples are not supported (JPEG 2000 Part 1 codes integers)");
  check_shape(image.width, image.height, image.channels, image.bits_per_sample, path);
  SourceImage out;
  out.width = image.width;
  out.height = image.height;
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  const std::int64_t lo = image.is_signed ? -(std::int64_t{1} << (image.bits_per_sample - 1)) : 0;
  const std::int64_t hi = image.is_signed ? (std::int64_t{1} << (image.bits_per_sample - 1)) - 1
                                          : (std::int64_t{1} << image.bits_per_sample) - 1;
  for (int c = 0; c < image.channels; ++c) {
    SourceComponent comp;
    comp.precision = image.bits_per_sample;
    comp.is_signed = image.is_signed;
    imageio::resize_with_huge_pages(comp.samples, n);
    for (std::size_t i = 0; i < n; ++i) {
      const float v = image.pixels[i * static_cast<std::size_t>(image.channels) + static_cast<std::size_t>(c)];
      const auto iv = static_cast<std::int64_t>(std::llround(v));
      if (static_cast<float>(iv) != v || iv < lo || iv > hi)
        throw EncodeError(path + ": sample value " + std::to_string(v) + " does not fit " +
                          std::to_string(image.bits_per_sample) + "-bit " + (image.is_signed ? "signed" : "unsigned") +
                          " integers");
      comp.samples[i] = static_cast<std::int32_t>(iv);
    }
    out.components.push_back(std::move(comp));
  }
  return out;
}

}  // namespace codec
