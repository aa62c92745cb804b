#include "codec/encoder/engine.h"

#include <utility>

#include "codec/encoder/dwt_choice.h"
#include "codec/structure/error.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"
#include "dwt_gpu/shared_gpu.h"

namespace codec {

EncodeEngine::~EncodeEngine() = default;

const EncodeEngine::Gpu& EncodeEngine::gpu(bool hardware, const std::function<Gpu()>& make, bool& made_now) {
  std::lock_guard lock(mutex_);
  std::optional<Gpu>& slot = hardware ? hardware_ : any_;
  made_now = !slot;
  if (!slot) slot = make();
  return *slot;
}

namespace {

// The engine's GPU (made by whichever encode asked first, which reports its times and costs; the
// others find it ready) as a candidate for this encode.
GpuCandidate engine_gpu(EncodeEngine& engine, bool hardware, dwt::DwtBackend& cpu, DwtChoice& times) {
  bool made_now = false, measured_now = false;
  const EncodeEngine::Gpu& shared = engine.gpu(
      hardware,
      [&] {
        MadeGpu made = hardware ? make_hardware_gpu(cpu) : make_any_gpu();
        times.gl_context_ms = made.context_ms;
        times.shader_compile_ms = made.compile_ms;
        times.calibration_ms = made.calibration_ms;
        EncodeEngine::Gpu kept;
        kept.failure = made.failure;
        kept.costs = made.costs;
        measured_now = made.costs_measured_now;
        if (made.gpu) kept.gpu = std::make_shared<dwt_gpu::SharedGpu>(std::move(made.gpu));
        return kept;
      },
      made_now);
  GpuCandidate candidate;
  candidate.failure = shared.failure;
  candidate.costs = shared.costs;
  candidate.costs_measured_now = made_now && measured_now;
  if (shared.gpu) {
    candidate.renderer = shared.gpu->renderer();
    candidate.backend = std::make_unique<dwt_gpu::SharedGpuUser>(shared.gpu);
  }
  return candidate;
}

}  // namespace

DwtChoice choose_dwt(const EncodeParams& params, double samples, base::ThreadPool& pool) {
  if (params.lossless)
    return cpu_choice(std::make_unique<dwt_cpu::CpuBackend>(pool), "lossless: the reversible 5/3 runs on the CPU");
  DwtChoice choice;
  if (!params.engine || params.dwt == DwtDevice::Cpu) {
    choice = choose_dwt(params.dwt, samples, pool);
  } else {
    auto cpu = std::make_unique<dwt_cpu::CpuBackend>(pool);
    // As without an engine: where the cache gives the image to the CPU, no context is made.
    if (params.dwt == DwtDevice::Auto)
      if (auto reason = cpu_wins_here_by_cached_costs(cpu->name(), samples))
        return cpu_choice(std::move(cpu), std::move(*reason));
    DwtChoice times;
    GpuCandidate candidate = engine_gpu(*params.engine, params.dwt == DwtDevice::Auto, *cpu, times);
    choice = settle_dwt(params.dwt, std::move(candidate), std::move(cpu), samples);
    choice.gl_context_ms = times.gl_context_ms;
    choice.shader_compile_ms = times.shader_compile_ms;
    choice.calibration_ms = times.calibration_ms;
  }
  if (!choice.backend) throw EncodeError(choice.reason);
  return choice;
}

}  // namespace codec
