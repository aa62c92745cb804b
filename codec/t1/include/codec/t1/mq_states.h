#pragma once
#include <array>
#include <cstdint>

namespace codec::t1 {

// The MQ coder's probability state machine, T.800 Table C.2 ("Qe values and probability
// estimation"; identical to ITU-T T.88 Table E.1). One row per state index:
// Qe, the next index after an MPS, the next index after an LPS, and whether an LPS swaps the MPS.
struct MqStateRow {
  std::uint16_t qe;
  std::uint8_t nmps;
  std::uint8_t nlps;
  bool switch_mps;
};

inline constexpr int kMqStateCount = 47;

inline constexpr std::array<MqStateRow, kMqStateCount> kMqStates = {{
    {0x5601, 1, 1, true},    {0x3401, 2, 6, false},   {0x1801, 3, 9, false},   {0x0AC1, 4, 12, false},
    {0x0521, 5, 29, false},  {0x0221, 38, 33, false}, {0x5601, 7, 6, true},    {0x5401, 8, 14, false},
    {0x4801, 9, 14, false},  {0x3801, 10, 14, false}, {0x3001, 11, 17, false}, {0x2401, 12, 18, false},
    {0x1C01, 13, 20, false}, {0x1601, 29, 21, false}, {0x5601, 15, 14, true},  {0x5401, 16, 14, false},
    {0x5101, 17, 15, false}, {0x4801, 18, 16, false}, {0x3801, 19, 17, false}, {0x3401, 20, 18, false},
    {0x3001, 21, 19, false}, {0x2801, 22, 19, false}, {0x2401, 23, 20, false}, {0x2201, 24, 21, false},
    {0x1C01, 25, 22, false}, {0x1801, 26, 23, false}, {0x1601, 27, 24, false}, {0x1401, 28, 25, false},
    {0x1201, 29, 26, false}, {0x1101, 30, 27, false}, {0x0AC1, 31, 28, false}, {0x09C1, 32, 29, false},
    {0x08A1, 33, 30, false}, {0x0521, 34, 31, false}, {0x0441, 35, 32, false}, {0x02A1, 36, 33, false},
    {0x0221, 37, 34, false}, {0x0141, 38, 35, false}, {0x0111, 39, 36, false}, {0x0085, 40, 37, false},
    {0x0049, 41, 38, false}, {0x0025, 42, 39, false}, {0x0015, 43, 40, false}, {0x0009, 44, 41, false},
    {0x0005, 45, 42, false}, {0x0001, 45, 43, false}, {0x5601, 46, 46, false},
}};

// The encoder works on a context packed as (state index << 1) | MPS, so one lookup yields Qe and
// both successors with the MPS swap already folded in. This table is derived from the one above.
struct MqTransition {
  std::uint16_t qe;
  std::uint8_t next[2];  // packed context after coding [0] the LPS, [1] the MPS
};

inline constexpr std::array<MqTransition, 2 * kMqStateCount> kMqTransitions = [] {
  std::array<MqTransition, 2 * kMqStateCount> t{};
  for (int state = 0; state < kMqStateCount; ++state)
    for (int mps = 0; mps < 2; ++mps) {
      const MqStateRow& row = kMqStates[static_cast<std::size_t>(state)];
      const int lps_mps = row.switch_mps ? 1 - mps : mps;
      t[static_cast<std::size_t>(2 * state + mps)] = MqTransition{
          row.qe, {static_cast<std::uint8_t>(2 * row.nlps + lps_mps), static_cast<std::uint8_t>(2 * row.nmps + mps)}};
    }
  return t;
}();

}  // namespace codec::t1
