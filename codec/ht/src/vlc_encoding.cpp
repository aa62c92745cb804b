#include "vlc_encoding.h"

#include <bit>
#include <stdexcept>
#include <string>

namespace codec::ht {

VlcEncodingTable::VlcEncodingTable(QuadRowKind kind) {
  // Each sample in e_k sends one MagSgn bit fewer, so the codeword that costs least is the one whose
  // length less its e_k count is smallest.
  const auto cost = [](int length, std::uint8_t e_k) { return length - std::popcount(static_cast<unsigned>(e_k)); };
  for (const CxtVlcRow& row : cxt_vlc_rows(kind)) {
    const bool residual = row.u_off != 0;
    // Without a residual the pattern is irrelevant (e_k is 0); with one, the row serves every
    // non-empty "at top" pattern inside rho that agrees with it on e_k.
    for (int at_top = residual ? 1 : 0; at_top < (residual ? 16 : 1); ++at_top) {
      if (residual && ((at_top & ~row.rho) != 0 || (row.e_k & at_top) != row.e_1)) continue;
      VlcCode& code = codes_[index(row.context, row.rho, residual, at_top)];
      if (code.length == 0 || cost(row.length, row.e_k) < cost(code.length, code.e_k))
        code = VlcCode{row.codeword, row.length, row.e_k};
    }
  }
  // Every quad the cleanup pass can meet must have a codeword: any context with any pattern
  // (context 0 only for significant quads: the MEL codes the empty one).
  for (int context = 0; context < 8; ++context)
    for (int rho = context == 0 ? 1 : 0; rho < 16; ++rho) {
      if (codes_[index(context, rho, false, 0)].length == 0)
        throw std::logic_error("CxtVLC table: no codeword for context " + std::to_string(context) + ", rho " +
                               std::to_string(rho));
      for (int at_top = 1; at_top < 16 && rho != 0; ++at_top)
        if ((at_top & ~rho) == 0 && codes_[index(context, rho, true, at_top)].length == 0)
          throw std::logic_error("CxtVLC table: no codeword for context " + std::to_string(context) + ", rho " +
                                 std::to_string(rho) + " with a residual");
    }
}

const VlcEncodingTable& vlc_encoding_table(QuadRowKind kind) {
  static const VlcEncodingTable initial(QuadRowKind::Initial), other(QuadRowKind::Other);
  return kind == QuadRowKind::Initial ? initial : other;
}

}  // namespace codec::ht
