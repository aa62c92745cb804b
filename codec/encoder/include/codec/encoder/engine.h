#pragma once
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "base/thread_pool.h"
#include "codec/encoder/dwt_choice.h"

namespace dwt_gpu {
class SharedGpu;
}

namespace codec {

// Worker threads and GPU contexts that several encodes share (gpuj2k::Engine): an encode given an
// engine (EncodeParams::engine) runs its stages on the engine's pool, and its 9/7 on the engine's
// GPU when it would have used one. Encodes on different threads take turns: the pool runs one
// parallel_for at a time, the GL context is current on one thread at a time (dwt_gpu::SharedGpu).
class EncodeEngine {
 public:
  explicit EncodeEngine(int threads) : pool_(threads) {}
  ~EncodeEngine();
  EncodeEngine(const EncodeEngine&) = delete;
  EncodeEngine& operator=(const EncodeEngine&) = delete;

  base::ThreadPool& pool() { return pool_; }

  // One GPU as the engine keeps it: made by the first encode that asks, then shared; or why none
  // could be made (asked again, the answer is the same).
  struct Gpu {
    std::shared_ptr<dwt_gpu::SharedGpu> gpu;
    std::string failure;
    std::optional<DwtCosts> costs;  // the hardware GPU's, against this pool's CPU lifting
  };
  // The hardware GPU (--dwt auto) or any renderer (--dwt gpu), made with `make` under the engine's
  // lock if it is not there yet; `made_now` tells whether this call made it.
  const Gpu& gpu(bool hardware, const std::function<Gpu()>& make, bool& made_now);

 private:
  base::ThreadPool pool_;
  std::mutex mutex_;
  std::optional<Gpu> hardware_, any_;
};

}  // namespace codec
