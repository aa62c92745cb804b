#pragma once
#include <cstdint>
#include <string_view>

namespace dwt {

// How a signal is continued past its ends before filtering. The thesis keeps this as data (the
// indirect address table); the CPU backend uses the same function to fill its padded strips.
enum class Boundary {
  Symmetric,  // whole-sample symmetric: ... x2 x1 | x0 x1 ... xn-1 | xn-2 ... (JPEG 2000, T.800 F.3.7)
  Periodic,   // ... xn-2 xn-1 | x0 ... xn-1 | x0 x1 ...
  Zero,       // ... 0 0 | x0 ... xn-1 | 0 0 ...
};

Boundary parse_boundary(std::string_view name);  // "sym", "per", "zero"
std::string_view boundary_name(Boundary b);

// Index of the sample that stands at position `i` of the extended signal of length `n`, or -1
// where the extension is zero (and everywhere for an empty signal).
std::int64_t extend_index(std::int64_t i, std::int64_t n, Boundary b);

}  // namespace dwt
