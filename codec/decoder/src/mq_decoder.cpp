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

void MqDecoder::renormalise() {
  // RENORMD (Figure C.18).
  do {
    if (ct_ == 0) byte_in();
    a_ <<= 1;
    c_ <<= 1;
    --ct_;
  } while ((a_ & 0x8000) == 0);
}

int MqDecoder::decode(MqDecoderContext& cx) {
  // DECODE (Figure C.15) with LPS_EXCHANGE (C.17) and MPS_EXCHANGE (C.16).
  const t1::MqStateRow& row = t1::kMqStates[cx.state];
  const std::uint32_t qe = row.qe;
  int d;
  a_ -= qe;
  if ((c_ >> 16) < qe) {
    if (a_ < qe) {
      d = cx.mps;
      cx.state = row.nmps;
    } else {
      d = 1 - cx.mps;
      if (row.switch_mps) cx.mps = static_cast<std::uint8_t>(1 - cx.mps);
      cx.state = row.nlps;
    }
    a_ = qe;
    renormalise();
  } else {
    c_ -= qe << 16;
    if ((a_ & 0x8000) == 0) {
      if (a_ < qe) {
        d = 1 - cx.mps;
        if (row.switch_mps) cx.mps = static_cast<std::uint8_t>(1 - cx.mps);
        cx.state = row.nlps;
      } else {
        d = cx.mps;
        cx.state = row.nmps;
      }
      renormalise();
    } else {
      d = cx.mps;
    }
  }
  return d;
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
