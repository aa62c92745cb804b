#include "raw_writer.h"

namespace codec::t1 {

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
