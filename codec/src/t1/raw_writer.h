#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace codec::t1 {

// Raw (bypass) codeword segments of T.800 D.6: bits written as they are, most significant first,
// with a 0 stuffed into the MSB of every byte that follows a 0xFF so that no marker can appear.
class RawWriter {
 public:
  explicit RawWriter(std::vector<std::uint8_t>& out) : out_(&out) {}

  void start() {
    acc_ = 0;
    room_ = capacity_ = 8;
  }

  void put(int bit) {
    acc_ = (acc_ << 1) | static_cast<std::uint32_t>(bit);
    if (--room_ == 0) emit();
  }

  // Bytes a decoder needs to read every bit put so far (a partly filled byte counts whole).
  std::size_t truncation_length() const { return out_->size() + (room_ < capacity_ ? 1 : 0); }

  // Pads the last byte (with zeros, or with 0101... for predictable termination so that a
  // decoder can check it) and makes sure the segment does not end on 0xFF.
  void terminate(bool predictable);

 private:
  void emit() {
    const auto byte = static_cast<std::uint8_t>(acc_);
    out_->push_back(byte);
    acc_ = 0;
    room_ = capacity_ = byte == 0xFF ? 7 : 8;
  }

  std::vector<std::uint8_t>* out_;
  std::uint32_t acc_ = 0;
  int room_ = 8;      // bits still free in the byte being filled
  int capacity_ = 8;  // bits that byte holds in all: 7 after a 0xFF
};

}  // namespace codec::t1
