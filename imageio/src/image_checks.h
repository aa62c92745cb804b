#pragma once

#include <cstdint>
#include <string>

#include "imageio/image.h"

namespace imageio::detail {

// Largest sample count we allocate or accept (2^31): big enough for any
// realistic test or benchmark image, small enough that a corrupt header
// cannot make us allocate tens of gigabytes.
inline constexpr std::uint64_t kMaxSamples = std::uint64_t{1} << 31;

// Throws IoError(path, ...) unless the dimensions are positive and pixels
// holds exactly width * height * channels samples.
void check_layout(const std::string& path, const Image& image);

// Throws IoError(path, ...) unless every sample of an integer image is an
// integer within the range of bits_per_sample (1..16) and is_signed. Writers
// call it so that values are never clamped or rounded behind the caller's back.
void check_integer_samples(const std::string& path, const Image& image);

}  // namespace imageio::detail
