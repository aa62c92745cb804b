#include "codec/encoder/source_image.h"

#include <cmath>

#include "codec/structure/error.h"
#include "imageio/image.h"

namespace codec {

SourceImage to_source_image(const imageio::Image& image, const std::string& path) {
  if (image.is_float)
    throw EncodeError(path + ": floating-point samples are not supported (JPEG 2000 Part 1 codes integers)");
  if (image.bits_per_sample < 1 || image.bits_per_sample > 16)
    throw EncodeError(path + ": unsupported sample precision of " + std::to_string(image.bits_per_sample) + " bits");
  if (image.channels < 1 || image.channels > 16384)
    throw EncodeError(path + ": unsupported number of components (" + std::to_string(image.channels) + ")");
  if (image.width <= 0 || image.height <= 0) throw EncodeError(path + ": the image is empty");
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
    comp.samples.resize(n);
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
