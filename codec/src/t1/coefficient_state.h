#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "block_view.h"

namespace codec::t1 {

// Owns a code-block's working arrays (see BlockView): magnitudes and per-coefficient flags, the
// latter starting with only each coefficient's sign set.
class CoefficientState {
 public:
  CoefficientState(std::span<const std::int32_t> coefficients, int width, int height);

  // Magnitude bit-planes in use: the position of the highest set bit of any magnitude, plus one.
  int bit_planes() const { return bit_planes_; }
  BlockView view(bool causal);

 private:
  int width_;
  int height_;
  std::ptrdiff_t stride_;
  std::vector<std::uint16_t> flags_;
  std::vector<std::uint32_t> magnitude_;
  int bit_planes_ = 0;
};

}  // namespace codec::t1
