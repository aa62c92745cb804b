#pragma once
#include <cmath>
#include <cstdint>

namespace codec::t1 {

// Squared-error bookkeeping on the coefficient grid for a decoder that places a significant
// coefficient at the middle of its remaining uncertainty interval: with the bit-planes down to p
// known, magnitude m lies in [m_p, m_p + 2^p) (m_p keeps m's bits >= p) and is reconstructed as
// m_p + 2^(p-1); at p = 0 it is known exactly. The residual m - reconstruction is then
// (m mod 2^p) - 2^(p-1), or 0 at p = 0, which needs nothing but a mask and an offset.
//
// An irreversible coefficient is not its index: |c| / step = m + f with a fraction f, and after
// the last plane the decoder reconstructs m + 1/2, leaving f - 1/2. Measuring on the index alone
// would call that final error 0 and overrate the last planes, which are the most expensive ones;
// with coarse steps the rate allocator then buys them where finer planes elsewhere would do more.
// So the passes measure on the magnitude in fixed point, with F fraction bits appended
// (BlockView::fine): a plane p of the index is plane p + F of that number, and the final
// mid-point m + 1/2 is the mid-point rule at plane F. Both classes below are built with the
// shifted plane; DistortionSum scales its result back to index units.
class PlaneDistortion {
 public:
  explicit PlaneDistortion(int plane)
      : plane_(plane),
        low_mask_((std::uint32_t{1} << plane) - 1),
        low_half_(plane > 0 ? std::uint32_t{1} << (plane - 1) : 0),
        high_mask_((std::uint32_t{2} << plane) - 1),
        high_half_(std::uint32_t{1} << plane) {}

  // The coefficient becomes significant at this plane: its reconstruction leaves 0.
  std::int64_t significance_gain(std::uint32_t m) const {
    const std::int64_t before = m;
    return before * before - square(residual(m, low_mask_, low_half_));
  }

  // This plane's bit of a coefficient significant before: its interval halves. Negative at
  // times: the new mid-point can land further from m than the old one.
  std::int64_t refinement_gain(std::uint32_t m) const {
    return square(residual(m, high_mask_, high_half_)) - square(residual(m, low_mask_, low_half_));
  }

  // refinement_gain in DistortionSum's unit 2^(p-1) (1 at p = 0), without a multiplication: with
  // t = m mod 2^p and h = 2^(p-1) the residual goes from t - h to t (this plane's bit set) or to
  // t - 2h (clear), so the gain is h (2t - h) or h (3h - 2t). At p = 0 the magnitude becomes exact:
  // the error 1 of an even magnitude goes, an odd one had none.
  std::int64_t refinement_units(std::uint32_t m) const {
    const bool bit = (m >> plane_) & 1u;
    if (plane_ == 0) return bit ? 0 : 1;
    const auto t = static_cast<std::int64_t>(m & low_mask_), h = static_cast<std::int64_t>(low_half_);
    return bit ? 2 * t - h : 3 * h - 2 * t;
  }

 private:
  static std::int64_t residual(std::uint32_t m, std::uint32_t mask, std::uint32_t half) {
    return static_cast<std::int64_t>(m & mask) - half;
  }
  static std::int64_t square(std::int64_t x) { return x * x; }

  int plane_;
  std::uint32_t low_mask_, low_half_;    // planes below this one
  std::uint32_t high_mask_, high_half_;  // this plane and those below
};

// A pass's total, exact. Every gain at plane p is a multiple of 2^(p-1): a significance gain is
// m^2 - (m - r)^2 = r (2m - r) with the reconstruction r an odd multiple of 2^(p-1), a refinement
// gain (m - r1)^2 - (m - r2)^2 = (r2 - r1)(2m - r1 - r2) with r2 - r1 = +-2^(p-1). Counted in that
// unit a gain stays below 2^34 in magnitude, so a 64-bit sum cannot overflow however large the
// block, where the gains themselves (up to 2^62) could.
// With F fraction bits the fixed-point magnitude still stays below 2^31 (see CoefficientState),
// so the bound holds unchanged.
class DistortionSum {
 public:
  DistortionSum(int plane, int fraction_bits)
      : unit_log2_(plane > 0 ? plane - 1 : 0), scale_log2_(unit_log2_ - 2 * fraction_bits) {}
  void add(std::int64_t gain) { units_ += gain >> unit_log2_; }  // exact: see above
  void add_units(std::int64_t units) { units_ += units; }
  double value() const { return std::ldexp(static_cast<double>(units_), scale_log2_); }

 private:
  int unit_log2_;
  int scale_log2_;  // unit, back in index units squared
  std::int64_t units_ = 0;
};

}  // namespace codec::t1
