#pragma once
#include <array>
#include <cstdint>

#include "codec/ht/cxt_vlc_table.h"

namespace codec::ht {

struct VlcCode {
  std::uint8_t codeword = 0;
  std::uint8_t length = 0;
  std::uint8_t e_k = 0;  // samples whose top magnitude bit the codeword implies
};

// The encoder's view of a CxtVLC table: for a quad's context, significance pattern, whether it has
// a residual, and which samples have their exponent at U_q ("at top"), the shortest codeword whose
// EMB patterns agree: every sample in e_k must have its top bit equal to e_1 (T.814 7.3.5, 7.3.8).
// Built once from the standard's rows (cxt_vlc_table.cpp).
class VlcEncodingTable {
 public:
  explicit VlcEncodingTable(QuadRowKind kind);
  // The codes by index (simd::quad_row_analysis computes the indices, cleanup_encoder.cpp checks
  // that the two layouts agree): context << 9 | rho << 5 | has_residual << 4 | at_top, at_top 0
  // without a residual.
  static constexpr std::size_t index(int context, int rho, bool has_residual, int at_top) {
    return static_cast<std::size_t>((((context << 4 | rho) << 1 | (has_residual ? 1 : 0)) << 4) | at_top);
  }
  const VlcCode& at(std::size_t index) const { return codes_[index]; }
  static constexpr unsigned kRhoBits = 15u << 5;
  static constexpr int rho_of(std::size_t index) { return static_cast<int>((index >> 5) & 15); }
  static constexpr int context_of(std::size_t index) { return static_cast<int>(index >> 9); }

 private:
  std::array<VlcCode, 8 * 16 * 2 * 16> codes_{};
};

const VlcEncodingTable& vlc_encoding_table(QuadRowKind kind);

}  // namespace codec::ht
