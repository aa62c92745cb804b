#include "base/thread_pool.h"

#include <algorithm>

namespace base {

namespace {
// The pool whose parallel_for body this thread is running, if any: a nested call runs inline
// instead of waiting for the turn its own caller holds.
thread_local const ThreadPool* running_body_of = nullptr;
}  // namespace

ThreadPool::ThreadPool(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  if (threads <= 0) threads = 1;
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::run_items() {
  const ThreadPool* outer = running_body_of;
  running_body_of = this;
  struct Restore {
    const ThreadPool* outer;
    ~Restore() { running_body_of = outer; }
  } restore{outer};
  for (;;) {
    const std::size_t i = next_.fetch_add(1);
    if (i >= count_) return;
    try {
      (*body_)(i);
    } catch (...) {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      next_.store(count_);  // stop handing out work
    }
  }
}

void ThreadPool::worker_loop() {
  std::size_t seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    run_items();
    {
      std::lock_guard lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

void ThreadPool::parallel_for(std::size_t count, const std::function<void(std::size_t)>& body) {
  if (count == 0) return;
  if (workers_.empty() || count == 1 || running_body_of == this) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::lock_guard turn(turn_);
  {
    std::lock_guard lock(mutex_);
    body_ = &body;
    count_ = count;
    next_.store(0);
    error_ = nullptr;
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  wake_.notify_all();
  run_items();
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  body_ = nullptr;
  if (error_) std::rethrow_exception(error_);
}

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
  ThreadPool pool(static_cast<int>(chunks));
  pool.parallel_for((count + per_chunk - 1) / per_chunk, [&](std::size_t chunk) {
    const std::size_t begin = chunk * per_chunk;
    fn(begin, std::min(count, begin + per_chunk));
  });
}

}  // namespace base
