#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "imageio/image.h"

namespace testimages {

// Synthetic test images, so that tests and benchmarks never depend on
// downloaded photographs. Each targets something a wavelet codec must handle.
enum class Pattern {
  ZonePlate,     // concentric rings whose frequency rises to Nyquist at the edges
  GradientH,     // smooth ramp left to right
  GradientV,     // smooth ramp top to bottom
  GradientDiag,  // smooth ramp from the top-left corner to the bottom-right
  Edges,         // sharp steps, a checkerboard of varied cell sizes and a diagonal edge
  Noise,         // uniform white noise from a seeded 64-bit PRNG (SplitMix64)
  Mix,           // quadrants of the above: a natural-ish busy image
};

inline constexpr std::array<Pattern, 7> kAllPatterns = {
    Pattern::ZonePlate, Pattern::GradientH, Pattern::GradientV, Pattern::GradientDiag,
    Pattern::Edges,     Pattern::Noise,     Pattern::Mix,
};

// Names: zoneplate, gradient-h, gradient-v, gradient-diag, edges, noise, mix.
// An unknown name throws std::invalid_argument listing the valid ones.
Pattern parse_pattern(std::string_view name);
std::string_view pattern_name(Pattern pattern);

// Generates a width x height image with `channels` interleaved channels of
// integer samples using the full range of `bits` (1..16): 0..2^bits-1, or
// -2^(bits-1)..2^(bits-1)-1 when is_signed. Channels differ slightly from one
// another so colour transforms have something to do. Only Noise and Mix
// depend on `seed`.
//
// The output is bit-identical on every platform: only integer arithmetic is
// used (no libm, no floating-point rounding), and the noise comes from our
// own PRNG rather than <random> distributions.
//
// Throws std::invalid_argument for a side outside 1..65535, channels < 1,
// bits outside 1..16, or more than 2^31 samples in total.
imageio::Image generate(Pattern pattern, int width, int height, int channels, int bits, bool is_signed = false,
                        std::uint64_t seed = 1);

}  // namespace testimages
