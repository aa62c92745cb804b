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

SourceImage to_source_image(imageio::PlanarImage&& image, const std::string& path) {
  check_shape(image.width, image.height, image.channels, image.bits_per_sample, path);
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.planes.size() != static_cast<std::size_t>(image.channels))
    throw EncodeError(path + ": " + std::to_string(image.planes.size()) + " planes for " + std::to_string(image.channels) +
                      " components");
  SourceImage out;
  out.width = image.width;
  out.height = image.height;
  const std::int32_t top = (std::int32_t{1} << image.bits_per_sample) - 1;
  for (auto& plane : image.planes) {
    if (plane.size() != n) throw EncodeError(path + ": a plane of " + std::to_string(plane.size()) + " samples, not " + std::to_string(n));
    std::int32_t lo = 0, hi = 0;
    for (const std::int32_t v : plane) lo = std::min(lo, v), hi = std::max(hi, v);
    if (lo < 0 || hi > top)
      throw EncodeError(path + ": sample value " + std::to_string(lo < 0 ? lo : hi) + " does not fit " +
                        std::to_string(image.bits_per_sample) + "-bit unsigned integers");
    SourceComponent comp;
    comp.precision = image.bits_per_sample;
    comp.samples = std::move(plane);
    out.components.push_back(std::move(comp));
  }
  image.planes.clear();
  return out;
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
