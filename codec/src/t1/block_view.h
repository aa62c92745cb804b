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
  // What distortion is measured on: each magnitude with `fine_bits` bits of the coefficient's
  // fraction below its quantisation index appended (|c| / step in fixed point). With no fraction
  // known (reversible coding, where the index is the coefficient) this is `magnitude` itself and
  // fine_bits is 0.
  const std::uint32_t* fine = nullptr;
  int fine_bits = 0;

  std::ptrdiff_t index(int x, int y) const { return static_cast<std::ptrdiff_t>(y) * stride + x; }
};

// The flags of a full stripe column (four coefficients) combined: bits set in any, and in all.
struct ColumnSummary {
  unsigned any;
  unsigned all;
};

// Visits every coefficient in the scan order of T.800 D.1: stripes of four rows, top to bottom;
// within a stripe column by column, left to right; within a column top to bottom. `visit` gets
// the coefficient's index and its row within the stripe (0..3). Full columns for which
// `worth_visiting(ColumnSummary)` says no are skipped whole, saving four flag tests each.
template <class ColumnFilter, class Visit>
inline void for_each_in_scan_order(const BlockView& v, ColumnFilter&& worth_visiting, Visit&& visit) {
  const std::ptrdiff_t s = v.stride;
  for (int y0 = 0; y0 < v.height; y0 += 4) {
    const int rows = std::min(4, v.height - y0);
    for (int x = 0; x < v.width; ++x) {
      std::ptrdiff_t i = v.index(x, y0);
      if (rows == 4) {  // the common case, unrolled: a 4-trip loop costs a mispredicted exit
        const std::uint16_t* f = v.flags + i;
        const unsigned f0 = f[0], f1 = f[s], f2 = f[2 * s], f3 = f[3 * s];
        if (!worth_visiting(ColumnSummary{f0 | f1 | f2 | f3, f0 & f1 & f2 & f3})) continue;
        visit(i, 0);
        visit(i + s, 1);
        visit(i + 2 * s, 2);
        visit(i + 3 * s, 3);
        continue;
      }
      for (int row = 0; row < rows; ++row, i += s) visit(i, row);
    }
  }
}

}  // namespace codec::t1
