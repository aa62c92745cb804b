#pragma once
#include <cstddef>
#include <cstdint>

namespace codec::t1 {

// Per-coefficient coding state, one 16-bit word each. Besides the coefficient's own state it
// mirrors the significance (and, for the four direct neighbours, the sign) of the 8 neighbours,
// kept up to date when a coefficient becomes significant, so that every context of Annex D is a
// table lookup on bits already at hand rather than eight loads.
enum NeighbourFlag : std::uint16_t {
  kSigN = 1u << 0,  // neighbour above is significant
  kSigS = 1u << 1,  // below
  kSigW = 1u << 2,  // left
  kSigE = 1u << 3,  // right
  kSigNW = 1u << 4,
  kSigNE = 1u << 5,
  kSigSW = 1u << 6,
  kSigSE = 1u << 7,
  kNegN = 1u << 8,  // ... and negative (only meaningful with the matching kSig bit)
  kNegS = 1u << 9,
  kNegW = 1u << 10,
  kNegE = 1u << 11,
  kSig = 1u << 12,      // the coefficient itself is significant
  kVisited = 1u << 13,  // coded in this bit-plane's significance propagation pass
  kRefined = 1u << 14,  // has had at least one magnitude refinement bit coded
  kNeg = 1u << 15,      // the coefficient itself is negative
};

inline constexpr std::uint16_t kNeighbourMask = 0xFF;

// Index into the sign table: significance of N, S, W, E in the low nibble, their signs above.
inline unsigned sign_table_index(std::uint16_t f) { return (f & 0x0Fu) | ((f >> 4) & 0xF0u); }

// Marks the coefficient at `f` (inside a bordered array `stride` words wide) significant with the
// given sign and tells its neighbours. With vertically causal contexts (D.7), a coefficient on the
// first row of a stripe stays invisible to the stripe above, whose contexts must not depend on it.
inline void make_significant(std::uint16_t* f, std::ptrdiff_t stride, unsigned negative, bool hide_from_above) {
  f[0] |= static_cast<std::uint16_t>(kSig | (negative << 15));
  if (!hide_from_above) {
    f[-stride] |= static_cast<std::uint16_t>(kSigS | (negative << 9));
    f[-stride - 1] |= kSigSE;
    f[-stride + 1] |= kSigSW;
  }
  f[stride] |= static_cast<std::uint16_t>(kSigN | (negative << 8));
  f[stride - 1] |= kSigNE;
  f[stride + 1] |= kSigNW;
  f[-1] |= static_cast<std::uint16_t>(kSigE | (negative << 11));
  f[1] |= static_cast<std::uint16_t>(kSigW | (negative << 10));
}

}  // namespace codec::t1
