#include "image_checks.h"

#include <cmath>
#include <cstddef>

namespace imageio::detail {

void check_layout(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0) {
    throw IoError(path, "invalid image dimensions " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                            " with " + std::to_string(image.channels) + " channels");
  }
  const std::uint64_t expected =
      std::uint64_t(image.width) * std::uint64_t(image.height) * std::uint64_t(image.channels);
  if (image.pixels.size() != expected) {
    throw IoError(path, "image of " + std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                            std::to_string(image.channels) + " needs " + std::to_string(expected) +
                            " samples but holds " + std::to_string(image.pixels.size()));
  }
}

void check_integer_samples(const std::string& path, const Image& image) {
  const int bits = image.bits_per_sample;
  if (bits < 1 || bits > 16) {
    throw IoError(path,
                  "unsupported bits_per_sample " + std::to_string(bits) + " for an integer image (expected 1..16)");
  }
  const long lo = image.is_signed ? -(1L << (bits - 1)) : 0L;
  const long hi = image.is_signed ? (1L << (bits - 1)) - 1 : (1L << bits) - 1;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    // The range test comes first so NaN and infinities fail it too; within the range (|v| < 2^16)
    // the conversion to long is exact for integers and drops the fraction of any other value.
    if (!(v >= float(lo) && v <= float(hi)) || static_cast<float>(static_cast<long>(v)) != v) {
      throw IoError(path, "sample " + std::to_string(i) + " has value " + std::to_string(v) + ", not an integer in " +
                              std::to_string(lo) + ".." + std::to_string(hi) + " (" + std::to_string(bits) + "-bit " +
                              (image.is_signed ? "signed" : "unsigned") + ")");
    }
  }
}

}  // namespace imageio::detail
