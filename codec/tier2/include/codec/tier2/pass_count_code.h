#pragma once
#include "codec/tier2/header_bit_writer.h"

namespace codec::t2 {

// The most coding passes one code-block can add in one packet: Table B.4 has no codeword beyond.
inline constexpr int kMaxPassesPerPacket = 164;

// Writes the number of coding passes a code-block contributes to a packet (1..164) with the
// variable-length codewords of T.800 Table B.4 (B.10.6):
//   1 -> 0,  2 -> 10,  3..5 -> 11 + 2 bits (n-3),  6..36 -> 1111 + 5 bits (n-6),
//   37..164 -> 1111 11111 + 7 bits (n-37).
// Short codes for few passes because layers usually add a handful of passes per block.
void write_pass_count(int passes, HeaderBitWriter& out);

}  // namespace codec::t2
