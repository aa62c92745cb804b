#pragma once
// Tier-1's stripe-column state words and the context lookups of T.800 Annex D built on them,
// shared by the encoder (codec/t1) and the decoder (codec/decoder) so that both walk a code-block
// the same way.
#include <array>
#include <cstddef>
#include <cstdint>

#include "codec/t1/block_encoder.h"

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

// Rows 0-3 that are significant, as a 4-bit mask. A lookup on the four significance bits as they
// lie (bits 0, 3, 6 and 9 after one shift; 16 of the table's 586 entries are used), three
// operations where gathering them bit by bit took eleven.
inline unsigned significant_rows(std::uint32_t w) {
  static constexpr std::array<std::uint8_t, 0x24A> kGather = [] {
    std::array<std::uint8_t, 0x24A> t{};
    for (unsigned rows = 0; rows < 16; ++rows) {
      unsigned spread = 0;
      for (unsigned r = 0; r < 4; ++r)
        if (rows & (1u << r)) spread |= 1u << (3 * r);
      t[spread] = static_cast<std::uint8_t>(rows);
    }
    return t;
  }();
  return kGather[(w >> 4) & 0x249u];
}

// Whether each of rows 0-3 is significant or was coded by this bit-plane's significance pass: a
// stripe column the cleanup pass has nothing to do in. The visited bits are spread onto the
// significance bits by a lookup, about half the operations of gathering both into nibbles.
inline bool all_rows_significant_or_visited(std::uint32_t w) {
  static constexpr std::array<std::uint32_t, 16> kVisitedAsSelf = [] {
    std::array<std::uint32_t, 16> t{};
    for (int v = 0; v < 16; ++v)
      for (int r = 0; r < 4; ++r)
        if (v & (1 << r)) t[static_cast<std::size_t>(v)] |= self(r);
    return t;
  }();
  return ((w | kVisitedAsSelf[(w >> 24) & 0xFu]) & kSelfAll) == kSelfAll;
}

// Sign-coding index (kSignTable below) of row r: the significance of N, W, E and S in bits 0, 2,
// 4 and 6, where one shift of the word puts them; the signs of N and S in bits 1 and 3 (one shift
// of the word's sign bits), of W and E in bits 5 and 7 (from the neighbouring columns' words). A
// sign bit is only ever set with its significance. Some 13 operations where gathering the bits
// into nibbles took twice as many: this runs once per newly significant coefficient.
inline unsigned sign_index(std::uint32_t centre, const std::uint32_t* w, int r) {
  return ((centre >> (3 * r + 1)) & 0x55u) | ((centre >> (17 + r)) & 0x0Au) | ((w[-1] >> (14 + r)) & 0x20u) |
         ((w[1] >> (12 + r)) & 0x80u);
}
// The same with the column's own word read from `w`. The form above is for a pass that holds that
// word in a register while it works down the column's rows, and stores it once at the end: each
// row's decisions then wait on no store and reload of it.
inline unsigned sign_index(const std::uint32_t* w, int r) { return sign_index(w[0], w, r); }

// Marks row r of the column at `w` (in a bordered array of stripes `stride` words apart)
// significant with the given sign, and tells the five or eight columns whose windows hold it.
// With vertically causal contexts (D.7) row 0 stays invisible to the stripe above, whose contexts
// must not depend on it.
// `centre` is the column's own word (w[0], held by the caller; see sign_index).
inline void make_significant(std::uint32_t& centre, std::uint32_t* w, std::ptrdiff_t stride, int r, unsigned negative,
                             bool causal) {
  const int j = r + 1;
  centre |= sig(j, 1) | negative << (18 + j);
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
inline void make_significant(std::uint32_t* w, std::ptrdiff_t stride, int r, unsigned negative, bool causal) {
  std::uint32_t centre = w[0];
  make_significant(centre, w, stride, r, negative, causal);
  w[0] = centre;
}

}  // namespace column

// A coefficient's sign as the block loader records it, one 16-bit word per coefficient.
inline constexpr std::uint16_t kNeg = 1u << 15;

// The 19 context labels of T.800 Annex D: 0-8 zero coding (Table D.1), 9-13 sign coding
// (Table D.3), 14-16 magnitude refinement (Table D.4), then run-length and UNIFORM (D.3.4).
inline constexpr int kRefineFirstQuiet = 14;  // first refinement, no significant neighbour
inline constexpr int kRefineFirstBusy = 15;   // first refinement, some significant neighbour
inline constexpr int kRefineLater = 16;       // any later refinement
inline constexpr int kRunLengthContext = 17;
inline constexpr int kUniformContext = 18;
inline constexpr int kContextCount = 19;

// Magnitude refinement context (Table D.4) of row r of a stripe column word: 14 for a first
// refinement with no significant neighbour, 15 with one, 16 for every later refinement. A lookup
// rather than a branch: whether a neighbour is significant is close to random in busy blocks.
inline int refinement_context(std::uint32_t word, int r) {
  static constexpr std::uint8_t kContexts[4] = {kRefineFirstQuiet, kRefineFirstBusy, kRefineLater, kRefineLater};
  const unsigned refined = (word & column::refined(r)) ? 2u : 0u;
  return kContexts[refined | (((word >> (3 * r)) & column::kNeighbours) != 0 ? 1u : 0u)];
}

// Zero-coding context (Table D.1) from the counts of significant horizontal, vertical and
// diagonal neighbours. `h` and `v` are given as the band sees them: HL swaps them (its filters
// are transposed relative to LH), which the table builder below takes care of.
constexpr std::uint8_t zero_coding_context_lh(int h, int v, int d) {
  if (h == 2) return 8;
  if (h == 1) return v >= 1 ? 7 : (d >= 1 ? 6 : 5);
  if (v == 2) return 4;
  if (v == 1) return 3;
  return d >= 2 ? 2 : static_cast<std::uint8_t>(d);
}

constexpr std::uint8_t zero_coding_context_hh(int h, int v, int d) {
  const int hv = h + v;
  if (d >= 3) return 8;
  if (d == 2) return hv >= 1 ? 7 : 6;
  if (d == 1) return hv >= 2 ? 5 : (hv == 1 ? 4 : 3);
  return hv >= 2 ? 2 : static_cast<std::uint8_t>(hv);
}

// Indexed by a row's 9-bit neighbourhood in a stripe column word (above): NW, N, NE,
// W, the coefficient itself (ignored), E, SW, S, SE from bit 0 up.
using ZeroCodingTable = std::array<std::uint8_t, 512>;

constexpr ZeroCodingTable make_zero_coding_table(Orientation o) {
  ZeroCodingTable t{};
  for (unsigned n = 0; n < 512; ++n) {
    auto bit = [n](int b) { return static_cast<int>((n >> b) & 1u); };
    const int h = bit(3) + bit(5);
    const int v = bit(1) + bit(7);
    const int d = bit(0) + bit(2) + bit(6) + bit(8);
    switch (o) {
      case Orientation::LL:
      case Orientation::LH:
        t[n] = zero_coding_context_lh(h, v, d);
        break;
      case Orientation::HL:
        t[n] = zero_coding_context_lh(v, h, d);
        break;
      case Orientation::HH:
        t[n] = zero_coding_context_hh(h, v, d);
        break;
    }
  }
  return t;
}

inline constexpr ZeroCodingTable kZeroCodingLlLh = make_zero_coding_table(Orientation::LH);
inline constexpr ZeroCodingTable kZeroCodingHl = make_zero_coding_table(Orientation::HL);
inline constexpr ZeroCodingTable kZeroCodingHh = make_zero_coding_table(Orientation::HH);

inline const ZeroCodingTable& zero_coding_table(Orientation o) {
  switch (o) {
    case Orientation::HL:
      return kZeroCodingHl;
    case Orientation::HH:
      return kZeroCodingHh;
    default:
      return kZeroCodingLlLh;
  }
}

// Sign coding (Tables D.2 and D.3): the horizontal and vertical contributions, each the clamped
// sum of +1 per positive and -1 per negative significant neighbour, select a context and the
// predicted sign; the coder codes sign XOR prediction. Entry = (context << 1) | XORbit, indexed
// by column::sign_index().
constexpr int clamp_contribution(int sum) { return sum > 0 ? 1 : (sum < 0 ? -1 : 0); }

constexpr std::uint8_t sign_entry(int h, int v) {
  // Table D.3 as written, rows by horizontal contribution 1, 0, -1, columns by vertical 1, 0, -1:
  // {context label, XORbit}.
  constexpr std::uint8_t kTable[3][3][2] = {
      {{13, 0}, {12, 0}, {11, 0}},  // H = 1
      {{10, 0}, {9, 0}, {10, 1}},   // H = 0
      {{11, 1}, {12, 1}, {13, 1}},  // H = -1
  };
  const auto& e = kTable[1 - h][1 - v];
  return static_cast<std::uint8_t>((e[0] << 1) | e[1]);
}

using SignTable = std::array<std::uint8_t, 256>;

constexpr SignTable make_sign_table() {
  SignTable t{};
  for (unsigned i = 0; i < 256; ++i) {
    // As column::sign_index lays it out: significance of N, W, E, S in bits 0, 2, 4, 6, the signs
    // (1 = negative) of N, S in bits 1, 3 and of W, E in bits 5, 7.
    auto contribution = [i](unsigned sig_bit, unsigned neg_bit) {
      if (!(i & sig_bit)) return 0;
      return (i & neg_bit) ? -1 : 1;
    };
    const int v = clamp_contribution(contribution(0x01, 0x02) + contribution(0x40, 0x08));
    const int h = clamp_contribution(contribution(0x04, 0x20) + contribution(0x10, 0x80));
    t[i] = sign_entry(h, v);
  }
  return t;
}

inline constexpr SignTable kSignTable = make_sign_table();

}  // namespace codec::t1
