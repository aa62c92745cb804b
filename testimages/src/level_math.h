#pragma once

#include <cstdint>

// Integer helpers shared by the patterns. Integer-only arithmetic is what
// makes the generated images identical on every platform.

namespace testimages::detail {

// from + (to - from) * num / den, rounded to nearest; den > 0, 0 <= num <= den.
constexpr std::uint32_t lerp_level(std::uint32_t from, std::uint32_t to, std::uint64_t num, std::uint64_t den) {
  if (to >= from) return from + std::uint32_t(((to - from) * num * 2 + den) / (den * 2));
  return from - std::uint32_t(((from - to) * num * 2 + den) / (den * 2));
}

// Makes channels differ from one another while each keeps the pattern's
// shape: channel 0 as is, channel 1 inverted, channel 2 at reduced contrast
// (a quarter of the range cut from each end), then repeating.
constexpr std::uint32_t channel_variant(std::uint32_t level, std::uint32_t max_level, int c) {
  switch (c % 3) {
    case 0:
      return level;
    case 1:
      return max_level - level;
    default: {
      const std::uint32_t margin = max_level / 4;
      return lerp_level(margin, max_level - margin, level, max_level);
    }
  }
}

}  // namespace testimages::detail
