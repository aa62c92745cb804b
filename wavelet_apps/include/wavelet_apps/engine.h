// Forward transform, band operation, inverse transform: the one computation every application of
// thesis 4.7 is made of, on either backend.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "dwt/band_operation.h"
#include "dwt/params.h"
#include "dwt/plane.h"
#include "glcontext/context.h"

namespace wavelet_apps {

class WaveletEngine {
 public:
  virtual ~WaveletEngine() = default;
  // Does any expensive one-time set-up (the GPU's context and shaders) and returns one line naming
  // what runs: the CPU backend with its threads, or the GL renderer.
  virtual std::string prepare() = 0;
  // Forward-transforms `first` (and `second` when it has data), applies `ops` to the coefficients
  // (dwt::apply_band_operations' meaning), and inverse-transforms the result into `first`.
  virtual void process(dwt::PlaneSpan<float> first, dwt::PlaneSpan<const float> second, const dwt::DwtParams& params,
                       std::span<const dwt::BandOperation> ops) = 0;
};

enum class EngineKind { Cpu, Gpu };
EngineKind parse_engine_kind(std::string_view name);  // "cpu", "gpu"

// CPU: lifting, then the band operation on the coefficients in memory, then lifting back.
std::unique_ptr<WaveletEngine> make_cpu_engine(int threads);
// GPU: the coefficients stay in textures from upload to read-back (GpuBackend::process_bands).
// The context is created by prepare() or the first process().
std::unique_ptr<WaveletEngine> make_gpu_engine(glc::Platform platform);
std::unique_ptr<WaveletEngine> make_engine(EngineKind kind, int threads, glc::Platform platform);

}  // namespace wavelet_apps
