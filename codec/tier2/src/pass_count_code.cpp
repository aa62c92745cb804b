#include "codec/tier2/pass_count_code.h"

#include <stdexcept>
#include <string>

namespace codec::t2 {

void write_pass_count(int passes, HeaderBitWriter& out) {
  if (passes < 1 || passes > kMaxPassesPerPacket)
    throw std::invalid_argument("write_pass_count: " + std::to_string(passes) + " passes has no Table B.4 codeword");
  const auto n = static_cast<std::uint64_t>(passes);
  if (passes == 1) {
    out.put_bit(false);
  } else if (passes == 2) {
    out.put_bits(0b10, 2);
  } else if (passes <= 5) {
    out.put_bits(0b11, 2);
    out.put_bits(n - 3, 2);  // 00, 01, 10: 11 stays free as the escape to longer codes
  } else if (passes <= 36) {
    out.put_bits(0b1111, 4);
    out.put_bits(n - 6, 5);  // 00000..11110; 11111 escapes again
  } else {
    out.put_bits(0b111111111, 9);
    out.put_bits(n - 37, 7);
  }
}

}  // namespace codec::t2
