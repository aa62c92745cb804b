#include <stdexcept>
#include <string>

#include "canvas.h"
#include "testimages/patterns.h"

namespace testimages {
namespace {

constexpr int kMaxSide = 65535;
// Same limit as imageio's readers, so whatever we generate can be read back.
constexpr std::uint64_t kMaxSamples = std::uint64_t{1} << 31;

void check_arguments(int width, int height, int channels, int bits) {
  if (width < 1 || width > kMaxSide || height < 1 || height > kMaxSide) {
    throw std::invalid_argument("image size must be 1..65535 on each side, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  }
  if (channels < 1) {
    throw std::invalid_argument("channels must be at least 1, got " + std::to_string(channels));
  }
  if (bits < 1 || bits > 16) {
    throw std::invalid_argument("bits must be 1..16, got " + std::to_string(bits));
  }
  const std::uint64_t samples = std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(channels);
  if (samples > kMaxSamples) {
    throw std::invalid_argument("image too large: " + std::to_string(samples) + " samples, the limit is " +
                                std::to_string(kMaxSamples));
  }
}

detail::LevelFn level_function(Pattern pattern) {
  switch (pattern) {
    case Pattern::ZonePlate:
      return &detail::zoneplate_level;
    case Pattern::GradientH:
      return &detail::gradient_h_level;
    case Pattern::GradientV:
      return &detail::gradient_v_level;
    case Pattern::GradientDiag:
      return &detail::gradient_diag_level;
    case Pattern::Edges:
      return &detail::edges_level;
    case Pattern::Noise:
      return &detail::noise_level;
    case Pattern::Mix:
      return &detail::mix_level;
  }
  throw std::invalid_argument("invalid Pattern value " + std::to_string(int(pattern)));
}

}  // namespace

imageio::Image generate(Pattern pattern, int width, int height, int channels, int bits, bool is_signed,
                        std::uint64_t seed) {
  check_arguments(width, height, channels, bits);
  const detail::LevelFn level_of = level_function(pattern);
  const detail::Canvas canvas{width, height, channels, bits, (std::uint32_t{1} << bits) - 1, seed};
  // Signed samples are the unsigned levels shifted down by half the range,
  // the same mapping JPEG 2000's DC level shift undoes.
  const std::int32_t offset = is_signed ? std::int32_t{1} << (bits - 1) : 0;

  imageio::Image image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.bits_per_sample = bits;
  image.is_signed = is_signed;
  image.is_float = false;
  image.pixels.reserve(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        image.pixels.push_back(float(std::int32_t(level_of(canvas, x, y, c)) - offset));
      }
    }
  }
  return image;
}

}  // namespace testimages
