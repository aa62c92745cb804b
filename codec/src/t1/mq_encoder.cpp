#include "codec/t1/mq_encoder.h"

#include <algorithm>
#include <cassert>

namespace codec::t1 {

void MqEncoder::start() {
  segment_start_ = out_->size();
  a_ = 0x8000;
  c_ = 0;
  // 12, not 13: the byte before a new segment is never 0xFF here, because every segment this
  // coder ends drops a trailing 0xFF (and the raw writer never ends on one).
  ct_ = 12;
}

MqEncoder::AfterByteOut MqEncoder::byte_out(std::vector<std::uint8_t>& out, std::size_t segment_start,
                                            std::uint32_t c) {
  const bool has_last = out.size() > segment_start;
  if (has_last && out.back() == 0xFF) {
    // Bit stuffing: the byte after 0xFF carries 7 bits, its MSB left free to absorb a carry.
    out.push_back(static_cast<std::uint8_t>(c >> 20));
    return {c & 0xFFFFF, 7};
  }
  if (c & 0x8000000) {
    // Carry into the byte already written. The first byte of a segment never receives one: the
    // 12 initial shifts leave the whole initial interval below bit 27.
    assert(has_last);
    ++out.back();
    c &= 0x7FFFFFF;
    if (out.back() == 0xFF) {
      out.push_back(static_cast<std::uint8_t>(c >> 20));
      return {c & 0xFFFFF, 7};
    }
  }
  out.push_back(static_cast<std::uint8_t>(c >> 19));
  return {c & 0x7FFFF, 8};
}

void MqEncoder::flush() {
  if (untouched()) return;  // an empty segment needs no bytes: no symbol has to be decoded from it
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
