#pragma once
#include <vector>

#include "dwt/boundary.h"
#include "dwt/geometry.h"

namespace dwt_gpu {

// The thesis' indirect address table (section 4.5, figure 4.5). One row per level and axis; texel i
// of a row stands for position e = i - pad of the boundary-extended sequence and carries
//   R: the address to fetch for position e (-1: the extension is zero there),
//   G: the filter selector alpha of output sample e (when 0 <= e < length),
//   B: the base position beta of output sample e (where its convolution is centred).
// So boundary extension, filter selection and downsampling are all table data; the shader only
// looks up and convolves.
struct AddressTexel {
  float address = -1;
  float alpha = 0;
  float beta = 0;
};

// Filter selectors: the two kernels of the bank, and one-tap kernels for a lone sample (T.800
// F.4.7 keeps a lone even sample and doubles a lone odd one; the inverse halves it), whatever the
// boundary scheme.
enum Selector { kFirstKernel = 0, kSecondKernel = 1, kLoneEven = 2, kLoneOdd = 3 };

// Forward (analysis): output sample n < low count is low-pass (alpha 0), centred at the nth
// even-coordinate input; the rest are high-pass (alpha 1) centred at odd-coordinate inputs
// (equations 4.11 and 4.12 generalised to either origin parity). Addresses index the input.
std::vector<AddressTexel> forward_row(dwt::AxisSpan span, int pad, dwt::Boundary boundary);

// Inverse (synthesis): output sample m is centred at itself (beta = m) and its selector is its own
// class, picking the interleaved reconstruction kernel (figure 4.8). Addresses implement the
// virtual upsampling and interleaving of figure 4.7: position e fetches the Mallat-ordered
// coefficient that interleaving would have put at the extended position e.
std::vector<AddressTexel> inverse_row(dwt::AxisSpan span, int pad, dwt::Boundary boundary);

// All rows of a transform, as RGBA32F texels: row 2*d is level d+1 horizontally, row 2*d+1
// vertically. Width is the longest row (length + 2 * pad).
struct AddressTable {
  int width = 0;
  int rows = 0;
  int pad = 0;
  std::vector<float> rgba;  // rows * width * 4

  static int row_of(int level_index, bool vertical) { return 2 * level_index + (vertical ? 1 : 0); }
};

AddressTable build_table(const std::vector<dwt::LevelGeometry>& levels, int pad, dwt::Boundary boundary, bool inverse);

}  // namespace dwt_gpu
