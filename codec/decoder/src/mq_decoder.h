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
class MqDecoder {
 public:
  void start(std::span<const std::uint8_t> segment);
  int decode(MqDecoderContext& cx);

 private:
  std::uint8_t byte_at(std::size_t i) const { return i < data_.size() ? data_[i] : 0xFF; }
  void byte_in();
  void renormalise();

  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::uint32_t a_ = 0, c_ = 0;
  int ct_ = 0;
};

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
