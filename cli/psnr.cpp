#include "psnr.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace cli {
namespace {

std::string shape(const imageio::Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + " with " + std::to_string(image.channels) +
         (image.channels == 1 ? " channel" : " channels");
}

double db(double peak, double mse) {
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

}  // namespace

double peak_for_bits(int bits) {
  if (bits < 1 || bits > 32) throw std::invalid_argument("bits must be 1..32, got " + std::to_string(bits));
  return std::ldexp(1.0, bits) - 1.0;
}

PsnrResult psnr_with_peak(const imageio::Image& reference, const imageio::Image& test, double peak) {
  if (reference.width != test.width || reference.height != test.height || reference.channels != test.channels)
    throw std::invalid_argument("images differ in shape: reference is " + shape(reference) + ", test is " +
                                shape(test));
  if (reference.width <= 0 || reference.height <= 0 || reference.channels <= 0)
    throw std::invalid_argument("images are empty (" + shape(reference) + ")");
  if (!(peak > 0) || !std::isfinite(peak)) throw std::invalid_argument("the peak value must be positive");
  const auto channels = static_cast<std::size_t>(reference.channels);
  const std::size_t samples = static_cast<std::size_t>(reference.width) * static_cast<std::size_t>(reference.height);
  if (reference.pixels.size() != samples * channels || test.pixels.size() != samples * channels)
    throw std::invalid_argument("image sample buffers do not match their stated size");

  std::vector<double> sum(channels, 0.0);
  for (std::size_t i = 0; i < samples; ++i)
    for (std::size_t c = 0; c < channels; ++c) {
      const double d =
          static_cast<double>(reference.pixels[i * channels + c]) - static_cast<double>(test.pixels[i * channels + c]);
      sum[c] += d * d;
    }
  PsnrResult r;
  r.peak = peak;
  double total = 0;
  for (std::size_t c = 0; c < channels; ++c) {
    const double mse = sum[c] / static_cast<double>(samples);
    r.channel_mse.push_back(mse);
    r.channel_db.push_back(db(peak, mse));
    total += sum[c];
  }
  r.all_mse = total / (static_cast<double>(samples) * static_cast<double>(channels));
  r.all_db = db(peak, r.all_mse);
  return r;
}

PsnrResult psnr(const imageio::Image& reference, const imageio::Image& test, int bits) {
  return psnr_with_peak(reference, test, peak_for_bits(bits));
}

}  // namespace cli
