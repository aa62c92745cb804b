// Peak signal-to-noise ratio between two images of the same shape, per channel and over all
// channels, as used to compare lossy JPEG 2000 encodes with their source (thesis Table 4.2).
#pragma once

#include <vector>

#include "imageio/image.h"

namespace cli {

struct PsnrResult {
  double peak = 0;                  // the peak signal value the dB figures use
  std::vector<double> channel_db;   // PSNR per channel; +infinity where the channel is identical
  std::vector<double> channel_mse;  // mean squared error per channel
  double all_db = 0;                // PSNR of the MSE over every sample of every channel
  double all_mse = 0;               // mean of the channel MSEs (all channels have the same sample count)
};

// 2^bits - 1 for bits in 1..32.
double peak_for_bits(int bits);

// PSNR = 10 log10(peak^2 / MSE), MSE averaged over the width x height samples of a channel.
// Throws std::invalid_argument (one line) when the images differ in width, height or channel count,
// are empty, or `peak` is not positive.
PsnrResult psnr_with_peak(const imageio::Image& reference, const imageio::Image& test, double peak);

// psnr_with_peak with peak 2^bits - 1 (bits in 1..32, else std::invalid_argument).
PsnrResult psnr(const imageio::Image& reference, const imageio::Image& test, int bits);

}  // namespace cli
