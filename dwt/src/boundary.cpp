#include "dwt/boundary.h"

#include "dwt/error.h"

#include <string>

namespace dwt {

Boundary parse_boundary(std::string_view name) {
  if (name == "sym" || name == "symmetric") return Boundary::Symmetric;
  if (name == "per" || name == "periodic") return Boundary::Periodic;
  if (name == "zero") return Boundary::Zero;
  throw DwtError("unknown boundary extension '" + std::string(name) + "' (expected sym, per or zero)");
}

std::string_view boundary_name(Boundary b) {
  switch (b) {
    case Boundary::Symmetric:
      return "sym";
    case Boundary::Periodic:
      return "per";
    case Boundary::Zero:
      return "zero";
  }
  return "?";
}

std::int64_t extend_index(std::int64_t i, std::int64_t n, Boundary b) {
  if (i >= 0 && i < n) return i;
  if (n <= 0) return -1;  // an empty signal extends to nothing
  switch (b) {
    case Boundary::Zero:
      return -1;
    case Boundary::Periodic: {
      std::int64_t r = i % n;
      return r < 0 ? r + n : r;
    }
    case Boundary::Symmetric: {
      if (n == 1) return 0;
      // Whole-sample mirroring has period 2n-2; fold into one period, then reflect the back half.
      const std::int64_t period = 2 * n - 2;
      std::int64_t r = i % period;
      if (r < 0) r += period;
      return r < n ? r : period - r;
    }
  }
  return -1;
}

}  // namespace dwt
