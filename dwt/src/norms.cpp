#include "dwt/norms.h"

#include <cmath>
#include <vector>

#include "dwt/error.h"

namespace dwt {

double synthesis_norm_1d(const Kernel& kernel, int level, bool high) {
  if (level < 1 || level > 32) throw DwtError("synthesis_norm_1d: level out of range");
  // A unit coefficient in the middle of a long interleaved sequence (even positions are low-pass),
  // then one inverse level at a time: each reconstruction is the next finer level's low band.
  // The buffer doubles with every level, so the response never reaches its unextended ends.
  constexpr std::size_t kStart = 64;
  std::vector<double> y(kStart, 0.0);
  y[kStart / 2 + (high ? 1 : 0)] = 1.0;
  for (int l = level; l >= 1; --l) {
    lift_inverse_f64(kernel, y, 0);
    if (l > 1) {
      std::vector<double> up(2 * y.size(), 0.0);
      for (std::size_t i = 0; i < y.size(); ++i) up[2 * i] = y[i];
      y.swap(up);
    }
  }
  double energy = 0.0;
  for (double v : y) energy += v * v;
  return std::sqrt(energy);
}

double synthesis_norm(const Kernel& kernel, int level, Orientation o) {
  const bool high_x = o == Orientation::HL || o == Orientation::HH;
  const bool high_y = o == Orientation::LH || o == Orientation::HH;
  return synthesis_norm_1d(kernel, level, high_x) * synthesis_norm_1d(kernel, level, high_y);
}

}  // namespace dwt
