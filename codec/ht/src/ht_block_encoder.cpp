#include "codec/ht/ht_block_encoder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "cleanup_encoder.h"
#include "codec/t1/dead_zone.h"

namespace codec::ht {
namespace {

// A block as the cleanup pass takes it: magnitudes and signs, row by row, and for irreversible
// coding the fractions the indices drop.
struct LoadedBlock {
  int width = 0, height = 0;
  std::vector<std::uint32_t> magnitudes;
  std::vector<std::uint8_t> negative;
  std::vector<std::uint8_t> fractions;  // empty: reversible
};

void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > 1024 || height > 1024 || width * height > 4096)
    throw std::invalid_argument("HT block: a code-block of " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1..1024 with at most 4096 samples");
}

LoadedBlock load(std::span<const std::int32_t> coefficients, int width, int height, std::span<const std::uint8_t> fractions) {
  check_size(width, height);
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (coefficients.size() != n) throw std::invalid_argument("HT block: expected width * height coefficients");
  if (!fractions.empty() && fractions.size() != n) throw std::invalid_argument("HT block: expected one fraction per coefficient");
  LoadedBlock b{width, height, std::vector<std::uint32_t>(n), std::vector<std::uint8_t>(n), {}};
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t c = coefficients[i];
    b.magnitudes[i] = c < 0 ? static_cast<std::uint32_t>(0) - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
    b.negative[i] = c < 0 ? 1 : 0;
  }
  b.fractions.assign(fractions.begin(), fractions.end());
  return b;
}

// Squared error in the passes' units before any pass (the energy) and after the cleanup on plane
// p, with a significant magnitude reconstructed at the middle of what the decoder knows of it:
// exactly at p = 0 for indices, at index + 1/2 for irreversible coefficients.
struct ErrorSums {
  double energy = 0, after_cleanup = 0;
};

ErrorSums error_sums(const LoadedBlock& b, int p) {
  ErrorSums s;
  const bool irreversible = !b.fractions.empty();
  const double half_step = irreversible || p > 0 ? std::ldexp(1.0, p) / 2 : 0.0;
  for (std::size_t i = 0; i < b.magnitudes.size(); ++i) {
    const double value = static_cast<double>(b.magnitudes[i]) + (irreversible ? b.fractions[i] / 256.0 : 0.0);
    s.energy += value * value;
    const std::uint32_t mu = b.magnitudes[i] >> p;
    const double residual = mu == 0 ? value : value - (std::ldexp(static_cast<double>(mu), p) + half_step);
    s.after_cleanup += residual * residual;
  }
  return s;
}

t1::EncodedBlock encode_loaded(const LoadedBlock& b, int magnitude_bitplanes, int cleanup_plane, t1::Distortion distortion) {
  if (magnitude_bitplanes < 1 || magnitude_bitplanes > 31)
    throw std::invalid_argument("HT block: Mb must be 1..31, not " + std::to_string(magnitude_bitplanes));
  if (cleanup_plane < 0 || cleanup_plane >= magnitude_bitplanes)
    throw std::invalid_argument("HT block: the cleanup plane must be 0..Mb - 1, not " + std::to_string(cleanup_plane));
  std::uint32_t all = 0;
  for (std::uint32_t m : b.magnitudes) all |= m;
  t1::EncodedBlock out;
  out.bit_planes = static_cast<int>(std::bit_width(all));
  if (out.bit_planes > magnitude_bitplanes)
    throw std::invalid_argument("HT block: a magnitude needs " + std::to_string(out.bit_planes) + " bit-planes, over Mb = " +
                                std::to_string(magnitude_bitplanes));
  const ErrorSums sums = error_sums(b, cleanup_plane);
  out.energy = sums.energy;
  if (out.bit_planes <= cleanup_plane) {
    out.missing_msbs = magnitude_bitplanes;
    return out;
  }
  std::vector<std::uint32_t> mu(b.magnitudes.size());
  for (std::size_t i = 0; i < mu.size(); ++i) mu[i] = b.magnitudes[i] >> cleanup_plane;
  out.data = encode_cleanup(mu, b.negative, b.width, b.height);
  out.first_pass_planes = out.bit_planes - cleanup_plane;
  out.missing_msbs = magnitude_bitplanes - 1 - cleanup_plane;
  const double decrease = distortion == t1::Distortion::Measured ? sums.energy - sums.after_cleanup : 0.0;
  out.passes.push_back(t1::PassInfo{out.data.size(), decrease, true});
  return out;
}

}  // namespace

t1::EncodedBlock encode_ht_block(std::span<const std::int32_t> coefficients, int width, int height,
                                 int magnitude_bitplanes, int cleanup_plane, std::span<const std::uint8_t> fractions,
                                 t1::Distortion distortion) {
  return encode_loaded(load(coefficients, width, height, fractions), magnitude_bitplanes, cleanup_plane, distortion);
}

t1::EncodedBlock encode_ht_block(const t1::IntegerBlock& block, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion) {
  check_size(block.width, block.height);
  std::vector<std::int32_t> indices(static_cast<std::size_t>(block.width) * static_cast<std::size_t>(block.height));
  for (int y = 0; y < block.height; ++y)
    std::copy_n(block.origin + y * block.stride, block.width, indices.begin() + static_cast<std::ptrdiff_t>(y) * block.width);
  return encode_ht_block(indices, block.width, block.height, magnitude_bitplanes, cleanup_plane, {}, distortion);
}

t1::EncodedBlock encode_ht_block(const t1::FloatBlock& block, int magnitude_bitplanes, int cleanup_plane,
                                 t1::Distortion distortion) {
  check_size(block.width, block.height);
  const auto n = static_cast<std::size_t>(block.width) * static_cast<std::size_t>(block.height);
  std::vector<std::int32_t> indices(n);
  std::vector<std::uint8_t> fractions(n);
  for (int y = 0; y < block.height; ++y) {
    const float* row = block.origin + y * block.stride;
    const std::size_t base = static_cast<std::size_t>(y) * static_cast<std::size_t>(block.width);
    for (int x = 0; x < block.width; ++x)
      indices[base + static_cast<std::size_t>(x)] = t1::quantize(row[x], block.inverse_step, fractions[base + static_cast<std::size_t>(x)]);
  }
  return encode_ht_block(indices, block.width, block.height, magnitude_bitplanes, cleanup_plane, fractions, distortion);
}

}  // namespace codec::ht
