#include "backends.h"

#include <cstdio>
#include <stdexcept>

#include "dwt/kernel.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"

namespace dwtool {

namespace {

std::unique_ptr<dwt::DwtBackend> make_gpu_backend(const Request& request) {
  // The environment is only consulted here, so a bad GPUJ2K_GL never breaks CPU runs.
  const glc::Platform platform = request.gl ? *request.gl : glc::platform_from_env();
  return std::make_unique<dwt_gpu::GpuBackend>(platform);
}

}  // namespace

std::unique_ptr<dwt::DwtBackend> make_backend(const Request& request) {
  std::unique_ptr<dwt::DwtBackend> backend = request.backend == BackendKind::Gpu
                                                 ? make_gpu_backend(request)
                                                 : std::make_unique<dwt_cpu::CpuBackend>(request.threads);
  if (!backend->supports(request.params.kernel)) {
    const dwt::Kernel& kernel = dwt::get_kernel(request.params.kernel);
    // Not backend->name(): on the GPU that would create the GL context just to report an error.
    if (kernel.reversible) throw std::runtime_error("the reversible 5/3 runs on the CPU backend only");
    throw std::runtime_error("the " + std::string(kernel.description) + " kernel is not supported by the " +
                             (request.backend == BackendKind::Gpu ? "gpu" : "cpu") + " backend");
  }
  return backend;
}

std::string prepare(dwt::DwtBackend& backend) {
  if (auto* gpu = dynamic_cast<dwt_gpu::GpuBackend*>(&backend)) return gpu->renderer();
  return {};
}

std::string stage_times(const dwt::DwtBackend& backend) {
  if (const dwt::DeviceTimings* device = backend.device_timings()) {
    const dwt::DeviceTimings& t = *device;
    // Context and shader compile are left out: prepare() paid for them before the clock started.
    char text[128];
    std::snprintf(text, sizeof text, " (upload %.2f, compute %.2f, download %.2f ms)", t.upload_ms, t.compute_ms,
                  t.download_ms);
    return text;
  }
  return {};
}

}  // namespace dwtool
