#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace codec::t1 {

// A code-block's working state as the coding passes see it; owns nothing. Both arrays are laid
// out with a one-coefficient border all round (so neighbour updates and lookups need no bounds
// checks); `flags` and `magnitude` point at coefficient (0, 0) and share the indexing below.
struct BlockView {
  std::uint16_t* flags = nullptr;
  const std::uint32_t* magnitude = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;  // width + 2
  bool causal = false;        // vertically causal context formation (D.7)

  std::ptrdiff_t index(int x, int y) const { return static_cast<std::ptrdiff_t>(y) * stride + x; }
};

// Visits every coefficient in the scan order of T.800 D.1: stripes of four rows, top to bottom;
// within a stripe column by column, left to right; within a column top to bottom. `visit` gets
// the coefficient's index and its row within the stripe (0..3).
template <class Visit>
inline void for_each_in_scan_order(const BlockView& v, Visit&& visit) {
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    const int rows = std::min(4, v.height - y0);
    for (int x = 0; x < v.width; ++x) {
      std::ptrdiff_t i = v.index(x, y0);
      for (int row = 0; row < rows; ++row, i += v.stride) visit(i, row);
    }
  }
}

}  // namespace codec::t1
