#pragma once
#include <cstdint>

namespace codec::t1 {

// The code-block coding options of T.800 Table A.19 (the COD/COC SPcod "code-block style" byte).
// Each switch trades a little compression for parallelism, error resilience or decoder speed; the
// tier-1 coder honours all of them, alone or combined.
struct BlockStyle {
  bool bypass = false;                   // 0x01 selective arithmetic coding bypass (D.6)
  bool reset = false;                    // 0x02 reset context probabilities after every pass (D.4)
  bool terminate_each_pass = false;      // 0x04 terminate the coder after every pass (D.4)
  bool vertically_causal = false;        // 0x08 contexts ignore the stripe below (D.7)
  bool predictable_termination = false;  // 0x10 terminations a decoder can check (D.4.2)
  bool segmentation_symbols = false;     // 0x20 a 1010 symbol after every cleanup pass (D.5)

  // Bits outside the six above (0x40, 0x80: HT block coding in later parts) are ignored.
  static BlockStyle from_spcod(std::uint8_t bits);
  std::uint8_t to_spcod() const;

  friend bool operator==(const BlockStyle&, const BlockStyle&) = default;
};

}  // namespace codec::t1
