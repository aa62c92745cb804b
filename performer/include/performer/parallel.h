// Splitting per-vertex jobs across threads: the jobs are data parallel with no shared writes and
// take explicit ranges, so an engine embedding them could bring its own scheduler. The one
// implementation is base::parallel_for (a pool made for the call).
#pragma once

#include "base/thread_pool.h"

namespace performer {

using base::parallel_for;

}  // namespace performer
