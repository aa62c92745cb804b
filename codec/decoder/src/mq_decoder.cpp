#include "mq_decoder.h"

namespace codec::dec {

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
