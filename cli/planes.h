// Moving samples between imageio::Image (float storage, native integer values) and the planes the
// wavelet backends transform, with the checks that keep the reversible 5/3 exact.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "imageio/image.h"

namespace dwtool {

// The samples of a one-channel image, each checked to be finite (a NaN would spread over the whole
// plane and then defeat rounding and clamping). Errors name `path` and the sample's position.
std::vector<float> float_samples(const imageio::Image& image, const std::string& path);

// The samples as int32, each required to be an integer of magnitude at most 2^24, so that it and
// the transform's results round-trip through float32 files. `what` ("sample", "coefficient") and
// `path` go into the error message.
std::vector<std::int32_t> integer_samples(const imageio::Image& image, const std::string& path, const char* what);

// Integers back to float32 for a PFM file, refusing any beyond 2^24, where float32 stops being exact.
std::vector<float> exact_floats(const std::vector<std::int32_t>& values, int width, const std::string& path);

// A one-channel float32 image for write_pfm.
imageio::Image float_image(std::vector<float> samples, int width, int height);

struct IntegerImage {
  imageio::Image image;
  std::size_t clamped = 0;  // samples that fell outside [0, 2^bits - 1]
};

// Rounds to the nearest integer (halves away from zero) and clamps to [0, 2^bits - 1].
IntegerImage quantise(const std::vector<float>& samples, int width, int height, int bits);

}  // namespace dwtool
