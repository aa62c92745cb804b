#pragma once

#include <cstdint>

namespace testimages::detail {

// cos(2*pi * phase / 2^32) in Q30 fixed point (2^30 == 1.0), accurate to a
// few parts in 10^9. Computed with integer arithmetic only, because libm's
// cos may differ in the last bit between platforms and that could flip a
// rounded sample value.
std::int64_t fixed_cos(std::uint32_t phase);

}  // namespace testimages::detail
