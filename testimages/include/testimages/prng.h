#pragma once

#include <cstdint>

namespace testimages {

// SplitMix64 (Steele, Lea and Flood, 2014): tiny, fast, good enough for test
// data, and fully specified, so its output is identical everywhere, unlike
// std::rand or the <random> distributions.
inline constexpr std::uint64_t kSplitMix64Gamma = 0x9E3779B97F4A7C15ULL;

// The finaliser that turns a counter into a well-mixed 64-bit value.
constexpr std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// The index-th output (from 0) of a generator seeded with `seed`. The state
// only advances by a constant, so any output can be computed directly; this
// lets each pixel's noise be independent of the order pixels are visited.
constexpr std::uint64_t splitmix64_at(std::uint64_t seed, std::uint64_t index) {
  return splitmix64_mix(seed + (index + 1) * kSplitMix64Gamma);
}

class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}

  constexpr std::uint64_t next() {
    state_ += kSplitMix64Gamma;
    return splitmix64_mix(state_);
  }

 private:
  std::uint64_t state_;
};

}  // namespace testimages
