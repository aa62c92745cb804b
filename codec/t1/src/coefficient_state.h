#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "block_view.h"
#include "codec/t1/block_encoder.h"

namespace codec::t1 {

// (FloatBlockPlanes, FloatBlockSurvey and survey_float_block are in codec/t1/block_encoder.h.)
FloatBlockPlanes float_block_planes(const FloatBlock& block);
// The block's energy as CoefficientState(block).energy() gives it, without loading the block.
double float_block_energy(const FloatBlock& block, const FloatBlockPlanes& planes);

// A code-block's working arrays (see BlockView): magnitudes and signs, the stripe column words (all
// clear to begin with) and, when the coefficients' fractions are given, the fixed-point magnitudes
// distortion is measured on. The arrays are the calling thread's, reused from block to block (a
// 64x64 block's are some 48 KB, which allocating and clearing per block cost a few percent of
// tier-1); so a thread holds one CoefficientState at a time. Only the column words are cleared:
// every coefficient's magnitude, sign and fixed-point value is written by the load.
class CoefficientState {
 public:
  // `fractions`: empty, or one per coefficient (row by row like `coefficients`): the part of
  // |c| / step below the index, in 1/256ths (see encode_block).
  CoefficientState(std::span<const std::int32_t> coefficients, int width, int height,
                   std::span<const std::uint8_t> fractions = {});
  // The same from a block in its plane: indices as they are, or floats quantised on the way in.
  explicit CoefficientState(const IntegerBlock& block);
  explicit CoefficientState(const FloatBlock& block);
  CoefficientState(const FloatBlock& block, const FloatBlockPlanes& planes);

  // Magnitude bit-planes in use: the position of the highest set bit of any magnitude, plus one.
  int bit_planes() const { return bit_planes_; }
  // Sum of squared magnitudes in index units, fractions included: the error with nothing decoded.
  double energy() const { return energy_; }
  BlockView view(bool causal);

 private:
  CoefficientState(int width, int height);
  // Fills magnitudes and signs from `sample(x, y, fraction)` (returns the signed index, stores its
  // fraction when `with_fractions`), then the fixed-point magnitudes and the energy.
  template <class Sample>
  void load(Sample&& sample, bool with_fractions);

  // Calls f(i) for the index of every coefficient in the per-coefficient arrays, row by row.
  template <class F>
  void for_each_coefficient(F&& f) const;

  int width_;
  int height_;
  std::ptrdiff_t stride_;
  std::span<std::uint32_t> columns_;  // stripe column words (codec/t1/stripe_columns.h), bordered
  std::span<std::uint16_t> signs_;    // kNeg or 0 per coefficient; a border column each side, unused
  std::span<std::uint32_t> magnitude_;
  std::span<std::uint32_t> fine_;               // empty when no fractions were given
  std::span<std::uint32_t> column_magnitudes_;  // laid out as columns_ (BlockView::column_magnitudes)
  int fine_bits_ = 0;
  int bit_planes_ = 0;
  double energy_ = 0;
};

}  // namespace codec::t1
