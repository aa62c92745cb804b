#include "coefficient_state.h"

#include <bit>

#include "neighbourhood.h"

namespace codec::t1 {

CoefficientState::CoefficientState(std::span<const std::int32_t> coefficients, int width, int height)
    : width_(width),
      height_(height),
      stride_(width + 2),
      flags_(static_cast<std::size_t>(stride_ * (height + 2)), 0),
      magnitude_(flags_.size(), 0) {
  std::uint32_t any_bits = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::int32_t c = coefficients[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                          static_cast<std::size_t>(x)];
      // Negate in unsigned arithmetic: -INT32_MIN would overflow (the caller's Mb check rejects it).
      const std::uint32_t m = c < 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
      const auto i = static_cast<std::size_t>((y + 1) * stride_ + x + 1);
      magnitude_[i] = m;
      flags_[i] = c < 0 ? std::uint16_t{kNeg} : std::uint16_t{0};
      any_bits |= m;
    }
  // The OR of all magnitudes has the same highest set bit as their maximum, and is cheaper.
  bit_planes_ = static_cast<int>(std::bit_width(any_bits));
}

BlockView CoefficientState::view(bool causal) {
  const std::ptrdiff_t origin = stride_ + 1;
  return BlockView{flags_.data() + origin, magnitude_.data() + origin, width_, height_, stride_, causal};
}

}  // namespace codec::t1
