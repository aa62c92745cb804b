#pragma once
#include <cstddef>
#include <cstdint>

// Which stripe columns of up to 64 a coding pass has to look at, as a bit mask, vectorised with
// Highway and dispatched at run time: the passes then walk the set bits instead of loading every
// column's word to find it quiet. At low rates most columns of most coded bit-planes are quiet.
namespace codec::t1::simd {

inline constexpr std::size_t kMaskColumns = 64;

// Bit k (k < n <= 64) set where words[k] has any of `bits`.
std::uint64_t columns_with(const std::uint32_t* words, std::size_t n, std::uint32_t bits);

// Bit k (k < n <= 64) set where ((words[k] & bits) | (magnitudes[k] >> plane)) == 0: a cleanup pass's
// run-length column (nothing significant or visited in its window) with no 1 at the plane.
std::uint64_t quiet_columns(const std::uint32_t* words, const std::uint32_t* magnitudes, std::size_t n,
                            std::uint32_t bits, int plane);

}  // namespace codec::t1::simd
