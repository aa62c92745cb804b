#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

#include "codec/t1/mq_states.h"

namespace codec::dec {

// An adaptive probability context: index into T.800 Table C.2 and the current MPS.
struct MqDecoderContext {
  std::uint8_t state = 0;
  std::uint8_t mps = 0;
};

// The MQ arithmetic decoder of T.800 C.3 (INITDEC, DECODE, RENORMD, BYTEIN; Figures C.15-C.20),
// over one codeword segment. Past the segment's end it reads 0xFF bytes: BYTEIN then sees a
// marker and feeds 1-bits, as C.3.4 prescribes, so a short or truncated segment decodes to
// something bounded instead of reading outside its bytes.
//
// decode and renormalise are defined here, inline: tier-1 calls decode once per symbol, and the
// call was a fifth of a lossless decode's time.
class MqDecoder {
 public:
  void start(std::span<const std::uint8_t> segment);
  inline int decode(MqDecoderContext& cx);

 private:
  std::uint8_t byte_at(std::size_t i) const { return i < data_.size() ? data_[i] : 0xFF; }
  void byte_in();
  inline void renormalise();

  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::uint32_t a_ = 0, c_ = 0;
  int ct_ = 0;
};

inline void MqDecoder::renormalise() {
  // RENORMD (Figure C.18).
  do {
    if (ct_ == 0) byte_in();
    a_ <<= 1;
    c_ <<= 1;
    --ct_;
  } while ((a_ & 0x8000) == 0);
}

inline int MqDecoder::decode(MqDecoderContext& cx) {
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

// The raw (bypass) segments of D.6: bits MSB first, with the MSB of every byte after a 0xFF
// skipped (it is a stuffed 0). Past the end it reads 0xFF bytes.
class RawDecoder {
 public:
  void start(std::span<const std::uint8_t> segment);
  int bit();

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::uint8_t byte_ = 0;
  int bits_left_ = 0;
};

}  // namespace codec::dec
