#pragma once
#include <cstddef>
#include <cstdint>

// PNM rasters from integer rows (PnmRaster): n pixels of 1 or 3 planes, interleaved into
// bytes, 1 per sample (maxval up to 255) or 2 big-endian ones. Each returns the largest sample read
// as unsigned (a negative one is larger than any maxval), so that the caller checks the range once
// per chunk instead of once per sample; a sample outside 0..255 (0..65535) is written truncated,
// for the caller to refuse. The 8-bit ones are vectorised with Highway (dispatched at run time).
namespace imageio::detail {

std::uint32_t interleave_rgb8(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::uint8_t* out,
                              std::size_t n);
std::uint32_t interleave_grey8(const std::int32_t* grey, std::uint8_t* out, std::size_t n);
std::uint32_t interleave_rgb16(const std::int32_t* r, const std::int32_t* g, const std::int32_t* b, std::uint8_t* out,
                               std::size_t n);
std::uint32_t interleave_grey16(const std::int32_t* grey, std::uint8_t* out, std::size_t n);

}  // namespace imageio::detail
