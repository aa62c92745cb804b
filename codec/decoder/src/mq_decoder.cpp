#include "mq_decoder.h"

namespace codec::dec {

void MqDecoder::start(std::span<const std::uint8_t> segment) {
  // INITDEC (Figure C.20).
  data_ = segment;
  pos_ = 0;
  c_ = static_cast<std::uint32_t>(byte_at(0)) << 16;
  byte_in();
  c_ <<= 7;
  ct_ -= 7;
  a_ = 0x8000;
}

void MqDecoder::byte_in() {
  // BYTEIN (Figure C.19): a 0xFF followed by a byte above 0x8F is a marker (or the end), which
  // is never consumed; a 0xFF followed by anything else means the next byte has a stuffed bit.
  if (byte_at(pos_) == 0xFF) {
    if (byte_at(pos_ + 1) > 0x8F) {
      c_ += 0xFF00;
      ct_ = 8;
    } else {
      ++pos_;
      c_ += static_cast<std::uint32_t>(byte_at(pos_)) << 9;
      ct_ = 7;
    }
  } else {
    ++pos_;
    c_ += static_cast<std::uint32_t>(byte_at(pos_)) << 8;
    ct_ = 8;
  }
}

void RawDecoder::start(std::span<const std::uint8_t> segment) {
  data_ = segment;
  pos_ = 0;
  byte_ = 0;
  bits_left_ = 0;
}

int RawDecoder::bit() {
  if (bits_left_ == 0) {
    const bool after_ff = byte_ == 0xFF;
    byte_ = pos_ < data_.size() ? data_[pos_] : 0xFF;
    ++pos_;
    bits_left_ = after_ff ? 7 : 8;
  }
  --bits_left_;
  return (byte_ >> bits_left_) & 1;
}

}  // namespace codec::dec
