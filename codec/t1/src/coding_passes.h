#pragma once
#include "block_view.h"
#include "codec/t1/mq_encoder.h"
#include "contexts.h"
#include "raw_writer.h"

namespace codec::t1 {

// The three coding passes of T.800 D.3 over one bit-plane `plane`, each returning the decrease
// of squared error it buys (see distortion.h). The significance propagation and magnitude
// refinement passes come in an arithmetic-coded and a raw (bypass, D.6) form; cleanup passes
// are always arithmetic coded. Each comes in two instantiations: kMeasure false leaves out the
// distortion bookkeeping and returns 0.

template <bool kMeasure>
double significance_pass(const BlockView& v, int plane, const ZeroCodingTable& zc, ContextSet& cx, MqEncoder& mq);
template <bool kMeasure>
double significance_pass_raw(const BlockView& v, int plane, RawWriter& raw);

template <bool kMeasure>
double refinement_pass(const BlockView& v, int plane, ContextSet& cx, MqEncoder& mq);
template <bool kMeasure>
double refinement_pass_raw(const BlockView& v, int plane, RawWriter& raw);

// Also clears the per-plane "visited" marks the significance pass left, ready for the next plane.
template <bool kMeasure>
double cleanup_pass(const BlockView& v, int plane, const ZeroCodingTable& zc, ContextSet& cx, MqEncoder& mq);

}  // namespace codec::t1
