#include "codec/tier2/header_bit_writer.h"

#include <stdexcept>

namespace codec::t2 {

void HeaderBitWriter::put_bits(std::uint64_t value, int count) {
  if (count < 0 || count > 64) throw std::invalid_argument("HeaderBitWriter::put_bits: count out of 0..64");
  for (int i = count - 1; i >= 0; --i) put_bit(((value >> i) & 1) != 0);
}

void HeaderBitWriter::flush() {
  if (filled_ > 0) {
    out_.push_back(static_cast<std::uint8_t>(acc_ << (capacity_ - filled_)));
  } else if (capacity_ == 7) {
    // The header's last byte was 0xFF: the following (empty) byte still carries its stuffed bit.
    out_.push_back(0x00);
  }
  acc_ = 0;
  filled_ = 0;
  capacity_ = 8;
  bits_ = 0;
}

}  // namespace codec::t2
