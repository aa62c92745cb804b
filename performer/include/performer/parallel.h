// Splitting per-vertex jobs across threads. The jobs are data parallel with no shared writes, so
// contiguous chunks on plain std::threads are enough; there is no pool because a frame's skinning
// spawns a handful of threads at most, and an engine embedding this would bring its own scheduler
// (the jobs take explicit ranges for that reason).
#pragma once

#include <cstddef>
#include <functional>

namespace performer {

// Calls fn(begin, end) on disjoint ranges covering [0, count), each at least min_chunk long (but
// the last), on up to `threads` threads (0: hardware concurrency). The calling thread takes one
// chunk itself. The first exception thrown by any chunk is rethrown after all have finished.
void parallel_for(std::size_t count, std::size_t min_chunk, unsigned threads,
                  const std::function<void(std::size_t begin, std::size_t end)>& fn);

}  // namespace performer
