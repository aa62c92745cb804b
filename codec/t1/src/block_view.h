#pragma once
#include <cstddef>
#include <cstdint>

namespace codec::t1 {

// A code-block's working state as the coding passes see it; owns nothing.
// - `columns`: the stripe-column words of codec/t1/stripe_columns.h, stripe by stripe, `column_stride`
//   (width + 2) words apart, pointing at stripe 0's column 0; a border column on either side and a
//   border stripe above and below take the neighbour updates of the block's edges.
// - `magnitude` and `sign` (kNeg or 0), per coefficient row by row, `stride` (width + 2) apart,
//   pointing at coefficient (0, 0).
// - `column_magnitudes`, per stripe column (see below).
struct BlockView {
  std::uint32_t* columns = nullptr;
  std::ptrdiff_t column_stride = 0;
  const std::uint32_t* magnitude = nullptr;
  const std::uint16_t* sign = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;
  bool causal = false;  // vertically causal context formation (D.7)
  // What distortion is measured on: each magnitude with `fine_bits` bits of the coefficient's
  // fraction below its quantisation index appended (|c| / step in fixed point). With no fraction
  // known (reversible coding, where the index is the coefficient) this is `magnitude` itself and
  // fine_bits is 0.
  const std::uint32_t* fine = nullptr;
  int fine_bits = 0;
  // Per stripe column (laid out as `columns`): the OR of its rows' magnitudes, so whether any of
  // them has a bit at a plane takes one load.
  const std::uint32_t* column_magnitudes = nullptr;

  std::ptrdiff_t index(int x, int y) const { return static_cast<std::ptrdiff_t>(y) * stride + x; }
};

}  // namespace codec::t1
