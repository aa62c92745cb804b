#pragma once
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "codec/encoder/params.h"
#include "dwt/backend.h"
#include "base/thread_pool.h"

namespace dwt_gpu {
class GpuBackend;
}

namespace codec {

// What one forward 9/7 transform costs on each side, for the --dwt auto decision. Measured on the
// machine itself (calibrate_dwt), because the crossover moves with the CPU, its thread count and the
// GPU: on a 2-core laptop a discrete GPU may win at 512x512, on a 64-core server never.
struct DwtCosts {
  double cpu_ns_per_sample = 0;  // CPU lifting with the encoder's threads
  double gpu_setup_ms = 0;       // once per encode on an existing context: shader, first textures
  double gpu_ns_per_sample = 0;  // upload, render passes, download
};

// The GPU is used when its setup plus per-sample cost beat the CPU on `samples` (all components).
// The context itself is already made when this is asked, so its cost is not counted.
bool gpu_pays_off(const DwtCosts& costs, double samples);

// Times both backends on a 1024x1024 plane (twice each; the GPU's first run counts towards setup).
DwtCosts calibrate_dwt(dwt::DwtBackend& cpu, dwt_gpu::GpuBackend& gpu, double gpu_compile_ms);

// A small text cache of calibrations, one line per key (renderer, CPU backend, threads):
// $GPUJ2K_CACHE_DIR, else $XDG_CACHE_HOME/gpuj2k, else $HOME/.cache/gpuj2k, file dwt-costs.tsv.
// Reading a missing or damaged cache gives nothing; writing is best effort (temporary file, then
// rename), since a read-only home must not fail an encode.
std::optional<std::filesystem::path> dwt_cost_cache_path();
std::optional<DwtCosts> load_dwt_costs(const std::filesystem::path& cache, const std::string& key);
void store_dwt_costs(const std::filesystem::path& cache, const std::string& key, const DwtCosts& costs);

// The backend for the 9/7 and why it was chosen, for the report and the summary line.
struct DwtChoice {
  std::unique_ptr<dwt::DwtBackend> backend;
  std::string name;    // the backend, with the GL renderer for the GPU
  std::string reason;  // one line: "--dwt cpu", "no hardware GPU (...)", "GPU predicted 12 ms against 30 ms ..."
  double gl_context_ms = 0, shader_compile_ms = 0, calibration_ms = 0;
};

// --dwt cpu: the CPU. --dwt gpu: any GL context, software renderers included (for tests and
// comparisons), failing if there is none. --dwt auto: never a software rasteriser; on a hardware GPU
// only when the measured costs say it is faster for `samples`. The reversible 5/3 always runs on the
// CPU, so lossless encodes never make a context. CPU backends run on `pool`.
DwtChoice choose_dwt(const EncodeParams& params, double samples, base::ThreadPool& pool);

}  // namespace codec
