#pragma once
#include <cstddef>
#include <cstdint>

// The component transforms straight from an 8-bit interleaved RGB row (a PPM's raster, as the
// file held it) into the three planes, vectorised with Highway and dispatched at run time: one
// pass instead of unpacking each channel and transforming the unpacked rows. The values are those
// of component_transform.h's rct_forward_row and ict_forward_row, bit for bit.
namespace codec::simd {

void rct_forward_rgb8_row(const std::uint8_t* rgb, std::int32_t shift_r, std::int32_t shift_g, std::int32_t shift_b,
                          std::int32_t* y, std::int32_t* cb, std::int32_t* cr, std::size_t n);
void ict_forward_rgb8_row(const std::uint8_t* rgb, std::int32_t shift_r, std::int32_t shift_g, std::int32_t shift_b,
                          float* y, float* cb, float* cr, std::size_t n);

}  // namespace codec::simd
