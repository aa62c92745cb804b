#pragma once
#include <span>
#include <vector>

#include "dwt/geometry.h"
#include "dwt/plane.h"

namespace dwt {

// What becomes of the coefficients of one subband when one or two transformed planes are combined
// in the wavelet domain (thesis 4.7: scaling, removing and combining subbands). Both backends apply
// the same operations: the CPU with apply_band_operations below, the GPU as a fragment pass.
enum class BandRule {
  First,            // first_factor * a
  Second,           // second_factor * b
  Sum,              // first_factor * a + second_factor * b
  LargerMagnitude,  // whichever of first_factor * a and second_factor * b is larger in magnitude (a on ties)
};

struct BandOperation {
  LayoutRect rect;  // the band, in the Mallat layout (band_rect)
  BandRule rule = BandRule::First;
  float first_factor = 1.0f;
  float second_factor = 1.0f;
};

// Every band of a `levels`-level decomposition, in a fixed order: the coarsest LL first, then HL,
// LH, HH of the coarsest level, down to HH of level 1. Their rectangles tile the whole plane.
struct BandId {
  int level = 0;  // 1 = finest; LL carries the coarsest level's number (0 when levels == 0)
  Orientation orientation = Orientation::LL;
};
std::vector<BandId> all_bands(int levels);
// The rectangle of `band`; with levels == 0 the only band, LL, is the whole plane.
LayoutRect band_rect(const std::vector<LevelGeometry>& levels, const BandId& band, int width, int height);

// The formula of BandRule for one pair of coefficients.
inline float apply_rule(const BandOperation& op, float a, float b) {
  const float fa = op.first_factor * a;
  const float fb = op.second_factor * b;
  switch (op.rule) {
    case BandRule::First:
      return fa;
    case BandRule::Second:
      return fb;
    case BandRule::Sum:
      return fa + fb;
    case BandRule::LargerMagnitude:
      return (fb < 0 ? -fb : fb) > (fa < 0 ? -fa : fa) ? fb : fa;
  }
  return fa;
}

// Applies each operation to its rectangle, writing into `first`; `second` (same size) is only read
// by rules that name it and may be empty when none does. Samples outside every rectangle are left.
void apply_band_operations(PlaneSpan<float> first, PlaneSpan<const float> second, std::span<const BandOperation> ops);

}  // namespace dwt
