#include "raw_writer.h"

#include <algorithm>

namespace codec::t1 {

std::size_t minimal_raw_truncation_length(std::span<const std::uint8_t> data, const RawTruncationPoint& point,
                                          std::size_t segment_end, std::size_t lower_bound) {
  segment_end = std::min(segment_end, data.size());
  const std::size_t start = point.segment_start;
  const std::size_t lower = std::max(lower_bound, start);
  if (lower >= segment_end || point.committed > segment_end) return segment_end;
  // A 0 among the bits of the open byte: that byte is needed.
  if (point.open_bits > 0 && point.open != (std::uint32_t{1} << point.open_bits) - 1)
    return std::min(std::max(point.committed + 1, lower), segment_end);
  // Otherwise drop complete bytes from the end while all their bits are ones (0xFF, or 0x7F after
  // a 0xFF, whose MSB is the stuffed 0).
  std::size_t length = point.committed;
  while (length > lower) {
    const std::size_t j = length - 1;
    const unsigned ones = j > start && data[j - 1] == 0xFF ? 0x7Fu : 0xFFu;
    if (data[j] != ones) break;
    --length;
  }
  return std::max(length, lower);
}

void RawWriter::terminate(bool predictable) {
  // A segment must not end on 0xFF: the next segment's first byte could complete a marker code.
  // So the open byte is completed when it holds bits, and also when it is the one that has to
  // follow a 0xFF. Its first pad bit is 0 either way, so the completed byte is never 0xFF.
  const bool holds_bits = room_ < capacity_;
  const bool follows_ff = capacity_ == 7;
  if (!holds_bits && !follows_ff) return;
  const int pad_bits = room_;
  for (int i = 0; i < pad_bits; ++i) put(predictable ? (i & 1) : 0);
}

}  // namespace codec::t1
