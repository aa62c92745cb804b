#include "planes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace dwtool {

namespace {

// Largest magnitude up to which every integer is exactly a float32.
constexpr float kExactFloatLimit = 16777216.0f;  // 2^24

std::string shortest(float value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc{} ? std::string(buffer, end) : std::string("?");
}

std::string position(std::size_t index, int width) {
  const std::size_t w = static_cast<std::size_t>(width);
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "(" + std::string.
  std::string text = "(";
  text += std::to_string(index % w);
  text += ',';
  text += std::to_string(index / w);
  text += ')';
  return text;
}

}  // namespace

std::vector<float> float_samples(const imageio::Image& image, const std::string& path) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (!std::isfinite(image.pixels[i])) {
      throw std::runtime_error(path + ": sample at " + position(i, image.width) + " is " + shortest(image.pixels[i]) +
                               ", not a finite number");
    }
  }
  return image.pixels;
}

std::vector<std::int32_t> integer_samples(const imageio::Image& image, const std::string& path, const char* what) {
  std::vector<std::int32_t> out(image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    // The comparison is false for NaN, so NaN is refused here too.
    if (!(std::fabs(v) <= kExactFloatLimit) || std::trunc(v) != v) {
      throw std::runtime_error(path + ": " + what + " at " + position(i, image.width) + " is " + shortest(v) +
                               ", but the reversible 5/3 needs integers of magnitude at most 2^24");
    }
    out[i] = static_cast<std::int32_t>(v);
  }
  return out;
}

std::vector<float> exact_floats(const std::vector<std::int32_t>& values, int width, const std::string& path) {
  std::vector<float> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::int32_t v = values[i];
    if (v > (1 << 24) || v < -(1 << 24)) {
      throw std::runtime_error(path + ": value " + std::to_string(v) + " at " + position(i, width) +
                               " exceeds 2^24 and cannot be stored exactly as float32");
    }
    out[i] = static_cast<float>(v);
  }
  return out;
}

imageio::Image float_image(std::vector<float> samples, int width, int height) {
  imageio::Image image;
  image.width = width;
  image.height = height;
  image.channels = 1;
  image.bits_per_sample = 32;
  image.is_float = true;
  image.pixels = std::move(samples);
  return image;
}

IntegerImage quantise(const std::vector<float>& samples, int width, int height, int bits) {
  IntegerImage out;
  imageio::Image& image = out.image;
  image.width = width;
  image.height = height;
  image.channels = 1;
  image.bits_per_sample = bits;
  image.pixels.resize(samples.size());
  const float top = static_cast<float>((1 << bits) - 1);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const float rounded = std::round(samples[i]);
    if (std::isnan(rounded)) {  // only from overflowing coefficients; counted, not silently kept
      ++out.clamped;
      image.pixels[i] = 0.0f;
      continue;
    }
    const float clamped = std::clamp(rounded, 0.0f, top);
    if (clamped != rounded) ++out.clamped;
    image.pixels[i] = clamped;
  }
  return out;
}

}  // namespace dwtool
