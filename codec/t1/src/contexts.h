#pragma once
#include <array>
#include <cstdint>

#include "codec/t1/block_encoder.h"
#include "codec/t1/mq_encoder.h"
#include "neighbourhood.h"

namespace codec::t1 {

// The 19 context labels of T.800 Annex D: 0-8 zero coding (Table D.1), 9-13 sign coding
// (Table D.3), 14-16 magnitude refinement (Table D.4), then run-length and UNIFORM (D.3.4).
inline constexpr int kRefineFirstQuiet = 14;  // first refinement, no significant neighbour
inline constexpr int kRefineFirstBusy = 15;   // first refinement, some significant neighbour
inline constexpr int kRefineLater = 16;       // any later refinement
inline constexpr int kRunLengthContext = 17;
inline constexpr int kUniformContext = 18;
inline constexpr int kContextCount = 19;

using ContextSet = std::array<MqContext, kContextCount>;

// Magnitude refinement context (Table D.4) of row r of a stripe column word: 14 for a first
// refinement with no significant neighbour, 15 with one, 16 for every later refinement. A lookup
// rather than a branch: whether a neighbour is significant is close to random in busy blocks.
inline int refinement_context(std::uint32_t word, int r) {
  static constexpr std::uint8_t kContexts[4] = {kRefineFirstQuiet, kRefineFirstBusy, kRefineLater, kRefineLater};
  const unsigned refined = (word & column::refined(r)) ? 2u : 0u;
  return kContexts[refined | (((word >> (3 * r)) & column::kNeighbours) != 0 ? 1u : 0u)];
}

// Initial states (T.800 D.4): UNIFORM 46, run-length 3, the all-zero neighbourhood
// zero-coding context 4, everything else 0; every MPS 0.
inline void reset_contexts(ContextSet& cx) {
  cx.fill(MqContext(0, 0));
  cx[0] = MqContext(4, 0);
  cx[kRunLengthContext] = MqContext(3, 0);
  cx[kUniformContext] = MqContext(46, 0);
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

// Indexed by a row's 9-bit neighbourhood in a stripe column word (neighbourhood.h): NW, N, NE,
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
    // Low nibble: significance of N, S, W, E; high nibble: their signs (1 = negative).
    auto contribution = [i](unsigned sig_bit, unsigned neg_bit) {
      if (!(i & sig_bit)) return 0;
      return (i & neg_bit) ? -1 : 1;
    };
    const int v = clamp_contribution(contribution(0x1, 0x10) + contribution(0x2, 0x20));
    const int h = clamp_contribution(contribution(0x4, 0x40) + contribution(0x8, 0x80));
    t[i] = sign_entry(h, v);
  }
  return t;
}

inline constexpr SignTable kSignTable = make_sign_table();

}  // namespace codec::t1
