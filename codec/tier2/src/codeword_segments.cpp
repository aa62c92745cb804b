#include "codec/tier2/codeword_segments.h"

namespace codec::t2 {

bool segment_ends_after(const t1::BlockStyle& style, int pass, BlockCoder coder) {
  if (coder == BlockCoder::Ht) return pass % 3 != 1;  // each HT set: cleanup | SigProp + MagRef
  if (style.terminate_each_pass) return true;
  if (!style.bypass) return false;
  // Passes 0..9 are the first cleanup pass and three (significance, refinement, cleanup) triples,
  // all MQ-coded; the switch to raw coding after pass 9 ends that segment.
  if (pass < 10) return pass == 9;
  // From pass 10 the triple is (raw significance, raw refinement, MQ cleanup): the coder changes
  // after the refinement pass (raw -> MQ) and after the cleanup pass (MQ -> raw).
  return (pass - 10) % 3 != 0;
}

}  // namespace codec::t2
