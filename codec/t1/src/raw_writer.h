#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace codec::t1 {

// Where a raw segment could be cut: the bytes complete so far and the bits put into the open one.
struct RawTruncationPoint {
  std::size_t committed = 0;
  std::size_t segment_start = 0;
  int open_bits = 0;       // bits already in the byte being filled
  std::uint32_t open = 0;  // their values, the first in the most significant place
};

// The smallest L >= max(lower_bound, point.segment_start) such that a decoder given only
// data[point.segment_start, L) of the finished segment, reading 1 bits past it (the 0xFF fill,
// with its stuffing, yields nothing else), reads every bit put before `point` right: the bytes
// up to the one holding the last 0 bit put so far. Bytes before the cut are as written, so the
// decoder's bits agree with the writer's up to the cut whatever the stuffing after it; from there
// it reads ones, which is right exactly when every bit put there is a 1. At most segment_end.
std::size_t minimal_raw_truncation_length(std::span<const std::uint8_t> data, const RawTruncationPoint& point,
                                          std::size_t segment_end, std::size_t lower_bound);

// Raw (bypass) codeword segments of T.800 D.6: bits written as they are, most significant first,
// with a 0 stuffed into the MSB of every byte that follows a 0xFF so that no marker can appear.
class RawWriter {
 public:
  explicit RawWriter(std::vector<std::uint8_t>& out) : out_(&out) {}

  void start() {
    segment_start_ = out_->size();
    acc_ = 0;
    room_ = capacity_ = 8;
  }

  void put(int bit) {
    acc_ = (acc_ << 1) | static_cast<std::uint32_t>(bit);
    if (--room_ == 0) emit();
  }

  // Bytes a decoder needs to read every bit put so far (a partly filled byte counts whole).
  std::size_t truncation_length() const { return out_->size() + (room_ < capacity_ ? 1 : 0); }

  // The same point, to resolve with minimal_raw_truncation_length() once the segment is written.
  RawTruncationPoint truncation_point() const { return {out_->size(), segment_start_, capacity_ - room_, acc_}; }

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
  std::size_t segment_start_ = 0;
  std::uint32_t acc_ = 0;
  int room_ = 8;      // bits still free in the byte being filled
  int capacity_ = 8;  // bits that byte holds in all: 7 after a 0xFF
};

}  // namespace codec::t1
