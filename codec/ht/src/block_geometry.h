#pragma once
#include <array>
#include <stdexcept>
#include <string>

// What the HT block encoder and decoder both know of a code-block's shape.
namespace codec::ht {

// A quad's samples in the order of its significance pattern rho (T.814 7.3.1): top-left,
// bottom-left, top-right, bottom-right.
inline constexpr std::array<std::array<int, 2>, 4> kQuadOffsets{{{0, 0}, {0, 1}, {1, 0}, {1, 1}}};

// Throws std::invalid_argument for a code-block outside T.800's limits (each side 1..1024, at most
// 4096 samples).
inline void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > 1024 || height > 1024 || width * height > 4096)
    throw std::invalid_argument("HT block: a code-block of " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1..1024 with at most 4096 samples");
}

}  // namespace codec::ht
