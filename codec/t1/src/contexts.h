#pragma once
#include <array>
#include <cstdint>

#include "codec/t1/block_encoder.h"
#include "codec/t1/mq_encoder.h"
#include "codec/t1/stripe_columns.h"

namespace codec::t1 {

using ContextSet = std::array<MqContext, kContextCount>;

// Initial states (T.800 D.4): UNIFORM 46, run-length 3, the all-zero neighbourhood
// zero-coding context 4, everything else 0; every MPS 0.
inline void reset_contexts(ContextSet& cx) {
  cx.fill(MqContext(0, 0));
  cx[0] = MqContext(4, 0);
  cx[kRunLengthContext] = MqContext(3, 0);
  cx[kUniformContext] = MqContext(46, 0);
}

}  // namespace codec::t1
