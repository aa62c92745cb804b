#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

// The HT refinement passes (T.814 7.4, 7.5), the encoder's view: after a cleanup on bit-plane p
// (p >= 1), the SigProp pass and the MagRef pass code bit-plane p - 1 as raw bits, in one codeword
// segment (HT refinement segment Dref): the SigProp bits forwards from its start, the MagRef bits
// backwards from its end.

namespace codec::ht {

struct RefinementSegment {
  // SigProp bytes, then MagRef bytes in the order they lie in the segment (the last written first).
  std::vector<std::uint8_t> bytes;
  std::size_t sigprop_bytes = 0;  // a truncation after the SigProp pass keeps this many
  // Samples (row-major index) that the SigProp pass makes significant: its distortion decrease.
  std::vector<std::size_t> became_significant;
};

// `magnitudes` and `negative` as for encode_cleanup but with every plane (the quantisation
// indices' magnitudes), row by row; `plane` the cleanup's plane p (1..31). Sizes as for
// encode_cleanup; throws std::invalid_argument otherwise.
// SigProp raising (README, "Raising near-significant samples"): with `fractions` (each magnitude's
// fraction in 256ths; plane <= 15), SigProp codes as significant every sample it visits whose
// magnitude * 256 + fraction reaches `threshold` (at most 2^(plane - 1) * 256), not only those
// with bit plane - 1 set; `negative` must then hold the signs of zero magnitudes too.
struct SigPropRaise {
  std::span<const std::uint8_t> fractions;  // empty: no raising
  std::int32_t threshold = 0;
};

// `lowered`: samples the cleanup coded one index lower (cleanup_encoder.h, CleanupLowering), whose
// bit plane - 1 MagRef sends as 1 (the lowered index's bits below the plane are all 1).
RefinementSegment encode_refinement(std::span<const std::uint32_t> magnitudes, std::span<const std::uint8_t> negative,
                                    int width, int height, int plane, const SigPropRaise& raise = {},
                                    std::span<const std::size_t> lowered = {});

}  // namespace codec::ht
