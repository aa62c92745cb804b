#pragma once
#include <memory>
#include <mutex>
#include <string>

#include "dwt/backend.h"
#include "dwt_gpu/gpu_backend.h"

namespace dwt_gpu {

// One GPU backend (one GL context, one compiled shader) that several threads use in turn, so that
// encodes running at once pay for the context once (gpuj2k::Engine). A GL context is current on
// one thread at a time: each use holds the lock, makes the context current where it runs and
// releases it before unlocking.
class SharedGpu {
 public:
  explicit SharedGpu(std::unique_ptr<GpuBackend> gpu);
  ~SharedGpu();
  SharedGpu(const SharedGpu&) = delete;
  SharedGpu& operator=(const SharedGpu&) = delete;

  const std::string& name() const { return name_; }
  const std::string& renderer() const { return renderer_; }

  // Runs fn(backend) with the context current on this thread and nobody else using it; returns
  // the backend's timings of that use.
  template <class Fn>
  dwt::DeviceTimings use(Fn&& fn) {
    std::lock_guard lock(mutex_);
    struct Release {
      GpuBackend& gpu;
      ~Release() { gpu.release_context(); }
    } release{*gpu_};
    fn(*gpu_);
    return gpu_->last_timings();
  }

 private:
  std::mutex mutex_;
  std::unique_ptr<GpuBackend> gpu_;
  std::string name_, renderer_;
};

// A DwtBackend over a SharedGpu for one user (one encode), with its own copy of its last
// transform's timings, which another user's transforms cannot overwrite.
class SharedGpuUser final : public dwt::DwtBackend {
 public:
  explicit SharedGpuUser(std::shared_ptr<SharedGpu> shared) : shared_(std::move(shared)) {}

  std::string name() const override { return shared_->name(); }
  bool supports(dwt::KernelId kernel) const override;
  void forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void forward(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;
  const dwt::DeviceTimings* device_timings() const override { return &timings_; }

 private:
  std::shared_ptr<SharedGpu> shared_;
  dwt::DeviceTimings timings_;
};

}  // namespace dwt_gpu
