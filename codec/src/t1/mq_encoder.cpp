#include "codec/t1/mq_encoder.h"

#include <algorithm>

namespace codec::t1 {

void MqEncoder::start() {
  segment_start_ = out_->size();
  a_ = 0x8000;
  c_ = 0;
  // 12, not 13: the byte before a new segment is never 0xFF here, because every segment this
  // coder ends drops a trailing 0xFF (and the raw writer never ends on one).
  ct_ = 12;
  coded_ = false;
}

void MqEncoder::flush() {
  if (!coded_) return;  // an empty segment needs no bytes: no symbol has to be decoded from it
  // SETBITS: the value in [C, C + A) with the most trailing ones, which the decoder's 0xFF fill
  // reproduces for free.
  const std::uint32_t top = c_ + a_;
  c_ |= 0xFFFF;
  if (c_ >= top) c_ -= 0x8000;
  c_ <<= ct_;
  byte_out();
  c_ <<= ct_;
  byte_out();
  if (has_last_byte() && out_->back() == 0xFF) out_->pop_back();
}

void MqEncoder::flush_predictable() {
  // Output the register bits down to bit 15 (the weight of A's leading one): the kept bits of C
  // followed by the decoder's one-fill then lie within [C, C + 2^15) which is inside [C, C + A).
  int bits_needed = 12 - ct_;
  while (bits_needed > 0) {
    c_ <<= ct_;
    ct_ = 0;
    byte_out();
    bits_needed -= ct_;  // the byte just written held ct_ (8, or 7 after 0xFF) register bits
  }
  if (has_last_byte() && out_->back() == 0xFF) out_->pop_back();
}

std::size_t safe_truncation_length(std::span<const std::uint8_t> data, const MqTruncationPoint& point,
                                   std::size_t segment_end) {
  segment_end = std::min(segment_end, data.size());
  std::size_t length = point.committed;
  int bits = point.buffered_bits;
  while (bits > 0 && length < segment_end) {
    const bool after_ff = length > point.segment_start && data[length - 1] == 0xFF;
    bits -= after_ff ? 7 : 8;
    ++length;
  }
  return std::min(length, segment_end);
}

}  // namespace codec::t1
