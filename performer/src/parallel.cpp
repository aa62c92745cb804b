#include "performer/parallel.h"

#include <algorithm>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace performer {

void parallel_for(std::size_t count, std::size_t min_chunk, unsigned threads,
                  const std::function<void(std::size_t, std::size_t)>& fn) {
  if (count == 0) return;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  min_chunk = std::max<std::size_t>(1, min_chunk);
  const std::size_t chunks = std::min<std::size_t>(threads, (count + min_chunk - 1) / min_chunk);
  if (chunks <= 1) {
    fn(0, count);
    return;
  }
  const std::size_t per_chunk = (count + chunks - 1) / chunks;

  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto run = [&](std::size_t begin, std::size_t end) {
    try {
      fn(begin, end);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!first_error) first_error = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(chunks - 1);
  for (std::size_t begin = per_chunk; begin < count; begin += per_chunk) {
    const std::size_t end = std::min(count, begin + per_chunk);
    try {
      workers.emplace_back(run, begin, end);
    } catch (const std::system_error&) {
      run(begin, end);  // out of threads: the work still gets done, just here
    }
  }
  run(0, std::min(count, per_chunk));
  for (std::thread& w : workers) w.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace performer
