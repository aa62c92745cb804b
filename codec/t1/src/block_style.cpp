#include "codec/t1/block_style.h"

namespace codec::t1 {

namespace {
// Bit positions of T.800 Table A.19.
constexpr std::uint8_t kBypass = 0x01;
constexpr std::uint8_t kReset = 0x02;
constexpr std::uint8_t kTerminateEachPass = 0x04;
constexpr std::uint8_t kVerticallyCausal = 0x08;
constexpr std::uint8_t kPredictableTermination = 0x10;
constexpr std::uint8_t kSegmentationSymbols = 0x20;
}  // namespace

BlockStyle BlockStyle::from_spcod(std::uint8_t bits) {
  BlockStyle s;
  s.bypass = (bits & kBypass) != 0;
  s.reset = (bits & kReset) != 0;
  s.terminate_each_pass = (bits & kTerminateEachPass) != 0;
  s.vertically_causal = (bits & kVerticallyCausal) != 0;
  s.predictable_termination = (bits & kPredictableTermination) != 0;
  s.segmentation_symbols = (bits & kSegmentationSymbols) != 0;
  return s;
}

std::uint8_t BlockStyle::to_spcod() const {
  std::uint8_t bits = 0;
  if (bypass) bits |= kBypass;
  if (reset) bits |= kReset;
  if (terminate_each_pass) bits |= kTerminateEachPass;
  if (vertically_causal) bits |= kVerticallyCausal;
  if (predictable_termination) bits |= kPredictableTermination;
  if (segmentation_symbols) bits |= kSegmentationSymbols;
  return bits;
}

}  // namespace codec::t1
