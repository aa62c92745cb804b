#pragma once
#include <cstdint>
#include <span>

#include "codec/t1/block_encoder.h"
#include "codec/t1/block_style.h"

namespace codec::t1 {

// What a T.800 decoder reconstructs from a code-block whose codeword it received up to and
// including coding pass `passes - 1` (pass 0 is the first cleanup pass, numbered as encode_block
// numbers them; `passes` = 0 means nothing received, a count above the block's pass total means
// everything). Computed from the coefficients alone, without coding or decoding anything, so that
// an encoder can measure the true error of any truncation point.
//
// `coefficients`: the quantisation indices encode_block was given (width * height, row by row,
// magnitudes below 2^magnitude_bitplanes). `out` receives width * height values, row by row, in
// units of the quantisation index (the caller multiplies by the step size).
//
// Mid-point reconstruction: a coefficient that is significant, with its magnitude bits known down
// to plane p >= 1 (so its magnitude m lies in [m_p, m_p + 2^p), m_p = m with the bits below p
// cleared), reconstructs at sign * (m_p + 2^(p-1)); one known in every plane at
// sign * (m + final_offset) (0.5 is the mid-point of the final quantisation interval, as OpenJPEG
// reconstructs irreversible bands; 0 for reversible ones). Insignificant coefficients reconstruct
// at 0. Which coefficients know which plane follows the passes exactly: in the plane being coded
// when the codeword ends, the significance propagation pass reaches only the coefficients with a
// significant neighbour at their turn in the scan (vertically causal contexts included), so
// after it, or after the refinement pass that follows it, only some coefficients of that plane
// have been coded. With final_offset 0 the squared error against `coefficients` is the block's
// energy minus the distortion_decrease of encode_block's first `passes` passes.
//
// Only style.vertically_causal affects the result, and `o` does not at all: contexts, bypass and
// terminations change the codeword, not which coefficients a pass codes. Both are taken so that
// the call mirrors encode_block's.
//
// Linear in the block size, allocation free. Throws std::invalid_argument for inconsistent
// arguments (as encode_block does, plus a negative `passes`, an `out` of the wrong size, or a
// final_offset outside [0, 1)).
void reconstruct(std::span<const std::int32_t> coefficients, int width, int height, Orientation o,
                 int magnitude_bitplanes, BlockStyle style, int passes, std::span<float> out,
                 float final_offset = 0.5f);

}  // namespace codec::t1
