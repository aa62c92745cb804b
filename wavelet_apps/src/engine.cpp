#include "wavelet_apps/engine.h"

#include <algorithm>
#include <vector>

#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"
#include "wavelet_apps/error.h"

namespace wavelet_apps {

namespace {

class CpuEngine final : public WaveletEngine {
 public:
  explicit CpuEngine(int threads) : backend_(threads) {}
  std::string prepare() override { return backend_.name(); }

  void process(dwt::PlaneSpan<float> first, dwt::PlaneSpan<const float> second, const dwt::DwtParams& params,
               std::span<const dwt::BandOperation> ops) override {
    dwt::PlaneSpan<const float> second_coefficients{};
    if (second.data != nullptr) {
      // The second plane is the caller's to keep: transform a copy.
      second_copy_.resize(static_cast<std::size_t>(second.width) * static_cast<std::size_t>(second.height));
      for (int y = 0; y < second.height; ++y)
        std::copy(second.row(y), second.row(y) + second.width,
                  second_copy_.begin() + static_cast<std::ptrdiff_t>(y) * second.width);
      const auto span = dwt::make_span(second_copy_.data(), second.width, second.height);
      backend_.forward(span, params);
      second_coefficients = {span.data, span.width, span.height, span.stride};
    }
    backend_.forward(first, params);
    dwt::apply_band_operations(first, second_coefficients, ops);
    backend_.inverse(first, params);
  }

 private:
  dwt_cpu::CpuBackend backend_;
  std::vector<float> second_copy_;
};

class GpuEngine final : public WaveletEngine {
 public:
  explicit GpuEngine(glc::Platform platform) : backend_(platform) {}
  std::string prepare() override { return backend_.renderer(); }
  void process(dwt::PlaneSpan<float> first, dwt::PlaneSpan<const float> second, const dwt::DwtParams& params,
               std::span<const dwt::BandOperation> ops) override {
    backend_.process_bands(first, second, params, ops);
  }

 private:
  dwt_gpu::GpuBackend backend_;
};

}  // namespace

EngineKind parse_engine_kind(std::string_view name) {
  if (name == "cpu") return EngineKind::Cpu;
  if (name == "gpu") return EngineKind::Gpu;
  throw AppError("unknown backend '" + std::string(name) + "' (expected cpu or gpu)");
}

std::unique_ptr<WaveletEngine> make_cpu_engine(int threads) { return std::make_unique<CpuEngine>(threads); }
std::unique_ptr<WaveletEngine> make_gpu_engine(glc::Platform platform) { return std::make_unique<GpuEngine>(platform); }

std::unique_ptr<WaveletEngine> make_engine(EngineKind kind, int threads, glc::Platform platform) {
  return kind == EngineKind::Gpu ? make_gpu_engine(platform) : make_cpu_engine(threads);
}

}  // namespace wavelet_apps
