#include "dwt_gpu/shared_gpu.h"

namespace dwt_gpu {

SharedGpu::SharedGpu(std::unique_ptr<GpuBackend> gpu) : gpu_(std::move(gpu)) {
  name_ = gpu_->name();
  renderer_ = gpu_->renderer();
  // Made on the creating thread and current there: free it for whichever thread uses it first.
  gpu_->release_context();
}

// GL objects are deleted with their context current: the backend makes it current on this thread.
SharedGpu::~SharedGpu() = default;

bool SharedGpuUser::supports(dwt::KernelId kernel) const {
  bool result = false;
  shared_->use([&](GpuBackend& gpu) { result = gpu.supports(kernel); });
  return result;
}

void SharedGpuUser::forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) {
  timings_ = shared_->use([&](GpuBackend& gpu) { gpu.forward(plane, params); });
}

void SharedGpuUser::inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) {
  timings_ = shared_->use([&](GpuBackend& gpu) { gpu.inverse(plane, params); });
}

void SharedGpuUser::forward(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) {
  timings_ = shared_->use([&](GpuBackend& gpu) { gpu.forward(plane, params); });
}

void SharedGpuUser::inverse(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) {
  timings_ = shared_->use([&](GpuBackend& gpu) { gpu.inverse(plane, params); });
}

}  // namespace dwt_gpu
