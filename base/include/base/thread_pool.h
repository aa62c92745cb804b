#pragma once
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace base {

// A fixed set of worker threads that run one parallel_for at a time. The calling thread works too,
// so a pool of size 1 runs everything inline. Several threads may share a pool (encodes sharing a
// gpuj2k::Engine): their parallel_for calls take turns, each using every worker. A parallel_for
// called from inside a body of the same pool runs inline on the calling worker.
class ThreadPool {
 public:
  explicit ThreadPool(int threads = 0);  // 0: one per hardware thread
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls body(i) for every i in [0, count), spread over the threads; rethrows the first exception.
  void parallel_for(std::size_t count, const std::function<void(std::size_t)>& body);

 private:
  void worker_loop();
  void run_items();

  std::vector<std::thread> workers_;
  std::mutex turn_;  // held by the parallel_for that owns the workers
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(std::size_t)>* body_ = nullptr;
  std::size_t count_ = 0;
  std::atomic<std::size_t> next_{0};
  std::size_t generation_ = 0;
  int busy_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

// Calls fn(begin, end) on disjoint ranges covering [0, count), each at least min_chunk long (but
// the last), on up to `threads` threads (0: one per hardware thread), on a pool made for the call:
// for jobs that run now and then (a frame's skinning), where keeping threads would cost more. The
// first exception thrown by any range is rethrown after all have finished.
void parallel_for(std::size_t count, std::size_t min_chunk, unsigned threads,
                  const std::function<void(std::size_t begin, std::size_t end)>& fn);

}  // namespace base
