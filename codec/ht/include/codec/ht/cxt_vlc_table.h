#pragma once
#include <cstdint>
#include <span>

namespace codec::ht {

// One row of a CxtVLC table (T.814 Annex C): in quad context c_q, the significance pattern rho_q
// (bit i: sample i of the quad, in the order top-left, bottom-left, top-right, bottom-right) with
// u_off_q (whether an unsigned residual u_q follows) and the EMB patterns e_k (samples whose
// most significant magnitude bit, at exponent U_q, is implied rather than sent) and e_1 (the value
// of that implied bit) is sent as `length` bits of `codeword`, least significant bit first.
struct CxtVlcRow {
  std::uint8_t context;
  std::uint8_t rho;
  std::uint8_t u_off;
  std::uint8_t e_k;
  std::uint8_t e_1;
  std::uint8_t codeword;
  std::uint8_t length;
};

// Which table a quad uses (T.814 7.3.5): CxtVLC_table_0 for the first row of quads of a
// code-block, CxtVLC_table_1 for the others.
enum class QuadRowKind { Initial, Other };

// The rows of one table, in the standard's order.
std::span<const CxtVlcRow> cxt_vlc_rows(QuadRowKind kind);

}  // namespace codec::ht
