#pragma once
// Where the 9/7 runs (--dwt cpu|gpu|auto), decided the same way for the encoder's forward transform
// and the decoder's inverse one: the GL context, the calibration of both backends with its cache,
// and the decision with its reason. Neither the encoder's pipeline nor the decoder's is needed here.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "base/thread_pool.h"
#include "codec/dwt_choice/dwt_device.h"
#include "dwt/backend.h"

namespace dwt_gpu {
class GpuBackend;
}

namespace codec {

// What one 9/7 transform costs on each side, for the --dwt auto decision. Measured on the
// machine itself (calibrate_dwt), because the crossover moves with the CPU, its thread count and the
// GPU: on a 2-core laptop a discrete GPU may win at 512x512, on a 64-core server never. The
// inverse transform costs what the forward one does on both sides (the same filters, passes and
// transfers in the other order), so the decoder weighs the same costs.
struct DwtCosts {
  double cpu_ns_per_sample = 0;  // CPU lifting with the coder's threads
  double gpu_setup_ms = 0;       // once per image on an existing context: shader, first textures
  double gpu_ns_per_sample = 0;  // upload, render passes, download
  std::string renderer;          // the GPU they were measured on (GL_RENDERER and version), for reports
};

// The GPU is used when its setup plus per-sample cost beat the CPU on `samples` (all components).
// The context itself is already made when this is asked, so its cost is not counted.
bool gpu_pays_off(const DwtCosts& costs, double samples);

// Times both backends on a 1024x1024 plane (twice each; the GPU's first run counts towards setup).
DwtCosts calibrate_dwt(dwt::DwtBackend& cpu, dwt_gpu::GpuBackend& gpu, double gpu_compile_ms);

// A small text cache of calibrations, one line per key (the GPUs, the CPU backend and its threads),
// then the three costs and the renderer: $GPUJ2K_CACHE_DIR, else $XDG_CACHE_HOME/gpuj2k, else
// $HOME/.cache/gpuj2k, file dwt-costs.tsv. Reading a missing or damaged cache gives nothing; writing
// is best effort (temporary file, then rename), since a read-only home must not fail an encode or a
// decode.
std::optional<std::filesystem::path> dwt_cost_cache_path();
// The key: glc::hardware_gpu_fingerprint(), which needs no GL context, and the CPU backend's name.
std::string dwt_cost_key(const std::string& gpu_fingerprint, const std::string& cpu_name);
std::optional<DwtCosts> load_dwt_costs(const std::filesystem::path& cache, const std::string& key);
void store_dwt_costs(const std::filesystem::path& cache, const std::string& key, const DwtCosts& costs);

// The backend for the 9/7 and why it was chosen, for the report and the summary line. A null
// backend means --dwt gpu found no GL context at all; `reason` then says why, for the caller's
// own error.
struct DwtChoice {
  std::unique_ptr<dwt::DwtBackend> backend;
  std::string name;    // the backend, with the GL renderer for the GPU
  std::string reason;  // one line: "asked for the CPU", "no hardware GPU (...)", "the GPU is faster here: ..."
  double gl_context_ms = 0, shader_compile_ms = 0, calibration_ms = 0;
};

// A GL context with the DWT shader compiled, made for one image or for an engine, or why none.
struct MadeGpu {
  std::unique_ptr<dwt_gpu::GpuBackend> gpu;
  std::string failure;
  double context_ms = 0, compile_ms = 0, calibration_ms = 0;
  std::optional<DwtCosts> costs;  // hardware: the calibration against the CPU lifting
  bool costs_measured_now = false;
};

// --dwt gpu: any renderer, software ones included.
MadeGpu make_any_gpu();
// --dwt auto: a hardware GPU only, with its costs from the cache or measured now against `cpu`.
MadeGpu make_hardware_gpu(dwt::DwtBackend& cpu);

// A GPU as the decision weighs it: its backend (null: none could be made, and `failure` says why),
// its renderer and, for a hardware one, its costs.
struct GpuCandidate {
  std::unique_ptr<dwt::DwtBackend> backend;
  std::string renderer, failure;
  std::optional<DwtCosts> costs;
  bool costs_measured_now = false;
};

// --dwt auto before any GL context: where `cache` holds costs for `key` and they give `samples` to
// the CPU, the reason to say so; else nothing (no costs yet, or the GPU would win), and the context
// is made. On an NVIDIA H200 a context costs some 60-70 ms, twice a 2048x2048 encode's CPU DWT.
std::optional<std::string> cpu_wins_by_cached_costs(const std::optional<std::filesystem::path>& cache,
                                                    const std::string& key, double samples);
// The same on this machine: its GPUs (none: nothing), `cpu_name` and the cache in its usual place.
std::optional<std::string> cpu_wins_here_by_cached_costs(const std::string& cpu_name, double samples);

// The CPU for `reason`.
DwtChoice cpu_choice(std::unique_ptr<dwt::DwtBackend> cpu, std::string reason);

// --dwt gpu (`device` Gpu): the candidate, whatever its renderer. --dwt auto: the candidate only
// where its costs beat the CPU for `samples`, else `cpu`; the reason says which and by how much.
DwtChoice settle_dwt(DwtDevice device, GpuCandidate candidate, std::unique_ptr<dwt::DwtBackend> cpu, double samples);

// The whole choice for one image with a context of its own: --dwt cpu, gpu or auto as above; the
// CPU backend runs on `pool`. The GL times (context, compile, calibration) are reported.
DwtChoice choose_dwt(DwtDevice device, double samples, base::ThreadPool& pool);

}  // namespace codec
