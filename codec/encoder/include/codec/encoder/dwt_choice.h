#pragma once
// The encoder's side of --dwt (codec/dwt_choice/dwt_choice.h decides for encoder and decoder alike):
// lossless encodes and encodes sharing an engine's GPU.
#include "base/thread_pool.h"
#include "codec/dwt_choice/dwt_choice.h"
#include "codec/encoder/params.h"

namespace codec {

// --dwt cpu: the CPU. --dwt gpu: any GL context, software renderers included (for tests and
// comparisons), failing if there is none. --dwt auto: never a software rasteriser; on a hardware GPU
// only when the measured costs say it is faster for `samples`. The reversible 5/3 always runs on the
// CPU, so lossless encodes never make a context. CPU backends run on `pool`; with an engine
// (params.engine) its GPU is made once and shared.
DwtChoice choose_dwt(const EncodeParams& params, double samples, base::ThreadPool& pool);

}  // namespace codec
