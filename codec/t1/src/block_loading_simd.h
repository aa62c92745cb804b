#pragma once
#include <cstddef>
#include <cstdint>

// The row kernels that load a code-block into tier-1's working arrays (CoefficientState),
// vectorised with Highway and dispatched at run time to the best instruction set. Each handles
// one row of `n` coefficients; the arrays it writes are the state's, at the row's first
// coefficient.
namespace codec::t1::simd {

// The largest scaled magnitude min(|c| * inverse_step, kLargestMagnitude) of the row (dead_zone.h),
// a NaN counting as the clamp. Quantisation is monotonic in it, so its index is the row's largest.
float peak_scaled_magnitude(const float* row, std::size_t n, float inverse_step);

// Quantises a row of float coefficients: fine = floor(scaled magnitude * 2^fine_bits), the
// magnitude in fixed point with fine_bits fraction bits (the caller chooses fine_bits so that it
// stays below 2^31); magnitude = fine >> fine_bits, the quantisation index; flags = kNeg where the
// index is negative. Returns the sum of fine^2 (in units of 2^(-2 fine_bits)).
double quantize_row(const float* row, std::size_t n, float inverse_step, int fine_bits, std::uint32_t* fine,
                    std::uint32_t* magnitude, std::uint16_t* flags);

// quantize_row's returned sum alone (the same values), with nothing stored.
double fixed_point_energy_row(const float* row, std::size_t n, float inverse_step, int fine_bits);

// peak_scaled_magnitude and fixed_point_energy_row with 8 fraction bits in one pass: raises `peak`
// to the row's largest scaled magnitude and returns the sum. The sum is fixed_point_energy_row's
// (the same values, in the same order) wherever the peak leaves 8 fraction bits (a peak below
// 2^23); with a larger peak it is meaningless and the caller computes it again.
double peak_and_energy_row(const float* row, std::size_t n, float inverse_step, float& peak);

// Loads a row of integer indices (or reversible coefficients): magnitude = |c| (in unsigned
// arithmetic, so INT32_MIN gives 2^31), flags = kNeg where c < 0. Adds the sum of squared
// magnitudes to `energy` and returns the OR of the magnitudes.
std::uint32_t load_index_row(const std::int32_t* row, std::size_t n, std::uint32_t* magnitude, std::uint16_t* flags,
                             double& energy);

// out[x] = OR of rows[r * stride + x] for r < rows, x < n: a stripe's column magnitudes.
void or_stripe_rows(const std::uint32_t* rows, std::ptrdiff_t stride, int rows_in_stripe, std::size_t n,
                    std::uint32_t* out);

}  // namespace codec::t1::simd
