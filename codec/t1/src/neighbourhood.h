#pragma once
#include <cstddef>
#include <cstdint>

namespace codec::t1 {

// Tier-1's coding state, one 32-bit word per stripe column: the four coefficients T.800 D.1 scans
// together (rows 0-3 of a stripe, one column). Besides their own state the word mirrors the
// significance of everything around them, the 3x6 window of columns W, C, E by rows -1..4, kept up
// to date as coefficients become significant, so that a pass decides about a whole column with one
// load (skip it, or run-length code it) and every context of Annex D is a shift and a table lookup.
//
//   bits  0-17  significance of the window: row j - 1 (j = 0..5) at bits 3j (W), 3j + 1 (C), 3j + 2 (E)
//   bits 18-23  sign of column C's row j - 1 (1 = negative), set with its significance
//   bits 24-27  rows 0-3 coded by this bit-plane's significance propagation pass ("visited")
//   bits 28-31  rows 0-3 had a magnitude refinement bit coded before ("refined")
//
// Row r's 3x3 neighbourhood is then the 9 bits (word >> 3r) & 0x1FF: NW, N, NE, W, itself, E, SW,
// S, SE from bit 0 up.
namespace column {

constexpr std::uint32_t sig(int j, int k) { return 1u << (3 * j + k); }  // k: 0 W, 1 C, 2 E
constexpr std::uint32_t neg(int j) { return 1u << (18 + j); }
constexpr std::uint32_t self(int row) { return sig(row + 1, 1); }
constexpr std::uint32_t visited(int row) { return 1u << (24 + row); }
constexpr std::uint32_t refined(int row) { return 1u << (28 + row); }

inline constexpr std::uint32_t kWindow = 0x3FFFF;  // every significance bit
inline constexpr std::uint32_t kSelfAll = self(0) | self(1) | self(2) | self(3);
inline constexpr std::uint32_t kVisitedAll = 0xFu << 24;
inline constexpr std::uint32_t kNeighbourhood = 0x1FF;  // of row 0; shift by 3r for row r
inline constexpr std::uint32_t kCentre = 0x10;
inline constexpr std::uint32_t kNeighbours = kNeighbourhood & ~kCentre;

// Rows 0-3 that are significant, as a 4-bit mask.
inline unsigned significant_rows(std::uint32_t w) {
  return ((w >> 4) & 1u) | ((w >> 6) & 2u) | ((w >> 8) & 4u) | ((w >> 10) & 8u);
}

// Sign-coding index (contexts.h's kSignTable) of row r: significance of N, S, W, E in the low
// nibble, their signs above. W's and E's signs live in the neighbouring columns' words.
inline unsigned sign_index(const std::uint32_t* w, int r) {
  const std::uint32_t c = w[0];
  const unsigned n = (c >> (3 * r + 1)) & 1u, s = (c >> (3 * r + 7)) & 1u;
  const unsigned west = (c >> (3 * r + 3)) & 1u, east = (c >> (3 * r + 5)) & 1u;
  const unsigned n_neg = (c >> (18 + r)) & 1u, s_neg = (c >> (20 + r)) & 1u;
  const unsigned w_neg = (w[-1] >> (19 + r)) & 1u, e_neg = (w[1] >> (19 + r)) & 1u;
  return n | s << 1 | west << 2 | east << 3 | (n_neg & n) << 4 | (s_neg & s) << 5 | (w_neg & west) << 6 |
         (e_neg & east) << 7;
}

// Marks row r of the column at `w` (in a bordered array of stripes `stride` words apart)
// significant with the given sign, and tells the five or eight columns whose windows hold it.
// With vertically causal contexts (D.7) row 0 stays invisible to the stripe above, whose contexts
// must not depend on it.
inline void make_significant(std::uint32_t* w, std::ptrdiff_t stride, int r, unsigned negative, bool causal) {
  const int j = r + 1;
  w[0] |= sig(j, 1) | negative << (18 + j);
  w[-1] |= sig(j, 2);
  w[1] |= sig(j, 0);
  if (r == 0 && !causal) {
    std::uint32_t* above = w - stride;
    above[-1] |= sig(5, 2);
    above[0] |= sig(5, 1) | negative << 23;
    above[1] |= sig(5, 0);
  }
  if (r == 3) {
    std::uint32_t* below = w + stride;
    below[-1] |= sig(0, 2);
    below[0] |= sig(0, 1) | negative << 18;
    below[1] |= sig(0, 0);
  }
}

}  // namespace column

// A coefficient's sign as the block loader records it, one 16-bit word per coefficient.
inline constexpr std::uint16_t kNeg = 1u << 15;

}  // namespace codec::t1
