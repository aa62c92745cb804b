#include "codec/t1/reconstruction.h"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "pass_schedule.h"

namespace codec::t1 {

namespace {

void validate(std::span<const std::int32_t> coefficients, int width, int height, int magnitude_bitplanes, int passes,
              std::span<float> out, float final_offset) {
  if (width < 1 || height < 1)
    throw std::invalid_argument("code-block must be at least 1x1, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (coefficients.size() != n || out.size() != n)
    throw std::invalid_argument("code-block of " + std::to_string(width) + "x" + std::to_string(height) + " given " +
                                std::to_string(coefficients.size()) + " coefficients and " +
                                std::to_string(out.size()) + " outputs");
  if (magnitude_bitplanes < 0 || magnitude_bitplanes > 31)
    throw std::invalid_argument("magnitude bit-planes must be 0..31, got " + std::to_string(magnitude_bitplanes));
  if (passes < 0) throw std::invalid_argument("negative pass count " + std::to_string(passes));
  if (!(final_offset >= 0.0f && final_offset < 1.0f))  // also rejects NaN
    throw std::invalid_argument("final_offset must lie in [0, 1), got " + std::to_string(final_offset));
}

// Negated in unsigned arithmetic: -INT32_MIN would overflow (the Mb check rejects it afterwards).
inline std::uint32_t magnitude_of(std::int32_t c) {
  return c < 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c);
}

// The reconstruction of significant coefficients whose magnitude bits are known down to `plane`:
// the magnitude with the bits below `plane` cleared, plus half the interval left (or final_offset
// at plane 0). Computed exactly in double (magnitudes stay below 2^31) and rounded to float once.
class Midpoint {
 public:
  Midpoint(int plane, double final_offset)
      : keep_(~((std::uint32_t{1} << plane) - 1)),
        half_(plane > 0 ? static_cast<double>(std::uint32_t{1} << (plane - 1)) : final_offset) {}

  float operator()(std::int32_t c) const {
    const double r = static_cast<double>(magnitude_of(c) & keep_) + half_;
    return static_cast<float>(c < 0 ? -r : r);
  }

 private:
  std::uint32_t keep_;
  double half_;
};

// The significance propagation pass of one bit-plane, as far as membership goes. It visits the
// block in the scan order of T.800 D.1 (stripes of four rows; column by column; top to bottom)
// and writes each coefficient's reconstruction into `out` as it passes, so that `out` doubles as
// the pass's evolving significance state: a coefficient the scan has passed is significant iff
// its output is non-zero (a significant reconstruction is at least 1), one it has not reached yet
// still has its state from before the pass (significant iff its magnitude has a 1 above `plane`).
class SignificanceScan {
 public:
  SignificanceScan(std::span<const std::int32_t> c, std::span<float> out, int width, int height, int plane, bool causal)
      : c_(c), out_(out), w_(width), h_(height), plane_(plane), causal_(causal) {}

  // Whether (x, y) has a significant neighbour when the pass reaches it, so that the pass codes it.
  bool coded(int x, int y) const {
    const bool left = x > 0, right = x + 1 < w_;
    const int row = y & 3;  // stripes start on multiples of 4
    if (y > 0) {
      // The row above: all three passed if it is the previous stripe's last, else all but the right one.
      if ((left && passed(x - 1, y - 1)) || passed(x, y - 1)) return true;
      if (right && (row == 0 ? passed(x + 1, y - 1) : before(x + 1, y - 1))) return true;
    }
    if ((left && passed(x - 1, y)) || (right && before(x + 1, y))) return true;
    if (y + 1 < h_) {
      if (row == 3) {
        // The next stripe: none passed yet, and invisible altogether with vertically causal contexts (D.7).
        if (causal_) return false;
        return (left && before(x - 1, y + 1)) || before(x, y + 1) || (right && before(x + 1, y + 1));
      }
      return (left && passed(x - 1, y + 1)) || before(x, y + 1) || (right && before(x + 1, y + 1));
    }
    return false;
  }

 private:
  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x);
  }
  bool passed(int x, int y) const { return out_[at(x, y)] != 0.0f; }
  bool before(int x, int y) const { return (magnitude_of(c_[at(x, y)]) >> (plane_ + 1)) != 0; }

  std::span<const std::int32_t> c_;
  std::span<float> out_;
  int w_, h_;
  int plane_;
  bool causal_;
};

}  // namespace

void reconstruct(std::span<const std::int32_t> coefficients, int width, int height, Orientation /*o*/,
                 int magnitude_bitplanes, BlockStyle style, int passes, std::span<float> out, float final_offset) {
  validate(coefficients, width, height, magnitude_bitplanes, passes, out, final_offset);
  std::uint32_t any_bits = 0;
  for (std::int32_t c : coefficients) any_bits |= magnitude_of(c);
  const int planes = static_cast<int>(std::bit_width(any_bits));  // as encode_block counts them
  if (planes > magnitude_bitplanes)
    throw std::invalid_argument("a coefficient magnitude needs " + std::to_string(planes) + " bit-planes, Mb is " +
                                std::to_string(magnitude_bitplanes));

  const int received = std::min(passes, pass_count(planes));
  if (received == 0) {
    std::fill(out.begin(), out.end(), 0.0f);
    return;
  }
  const int last = received - 1;
  const int plane = pass_plane(last, planes);
  const double offset = final_offset;
  const std::size_t n = coefficients.size();

  // Every plane above `plane` is complete. After a cleanup pass so is `plane`: a coefficient is
  // significant iff it has a 1 at or above it, and knows every bit down to it.
  const Midpoint at_plane(plane, offset);
  if (pass_kind(last) == PassKind::Cleanup) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::int32_t c = coefficients[i];
      out[i] = (magnitude_of(c) >> plane) != 0 ? at_plane(c) : 0.0f;
    }
    return;
  }

  // The significance propagation pass of `plane`, perhaps followed by its refinement pass, was
  // received. Coefficients significant before the plane know bit `plane` only after the
  // refinement pass; those whose first 1 is at `plane` are significant (knowing their bits down
  // to `plane`) iff the significance pass coded them; anything else is still insignificant.
  const Midpoint earlier(pass_kind(last) == PassKind::Refinement ? plane : plane + 1, offset);
  const SignificanceScan scan(coefficients, out, width, height, plane, style.vertically_causal);
  for (int y0 = 0; y0 < height; y0 += 4) {
    const int y_end = std::min(y0 + 4, height);
    for (int x = 0; x < width; ++x)
      for (int y = y0; y < y_end; ++y) {
        const std::size_t i =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        const std::int32_t c = coefficients[i];
        const std::uint32_t high = magnitude_of(c) >> plane;
        float r = 0.0f;
        if (high > 1)
          r = earlier(c);
        else if (high == 1 && scan.coded(x, y))
          r = at_plane(c);
        out[i] = r;
      }
  }
}

}  // namespace codec::t1
