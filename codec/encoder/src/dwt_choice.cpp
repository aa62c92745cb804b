#include "codec/encoder/dwt_choice.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include "codec/structure/error.h"
#include "dwt_cpu/cpu_backend.h"
#include "codec/encoder/engine.h"
#include "dwt_gpu/gpu_backend.h"
#include "dwt_gpu/shared_gpu.h"
#include "glcontext/context.h"

namespace codec {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}

// Tabs and line breaks would break the cache's lines; renderer strings have none, but be sure.
std::string clean_key(std::string key) {
  for (char& c : key)
    if (c == '\t' || c == '\n' || c == '\r') c = ' ';
  return key;
}

}  // namespace

bool gpu_pays_off(const DwtCosts& costs, double samples) {
  const double gpu_ms = costs.gpu_setup_ms + costs.gpu_ns_per_sample * samples * 1e-6;
  const double cpu_ms = costs.cpu_ns_per_sample * samples * 1e-6;
  return gpu_ms < cpu_ms;
}

DwtCosts calibrate_dwt(dwt::DwtBackend& cpu, dwt_gpu::GpuBackend& gpu, double gpu_compile_ms) {
  constexpr int kSide = 1024;
  constexpr double kSamples = double{kSide} * kSide;
  std::vector<float> plane(static_cast<std::size_t>(kSide) * kSide);
  auto refill = [&] {  // a smooth ramp with some texture: values do not change the cost, only keep it honest
    for (std::size_t i = 0; i < plane.size(); ++i) plane[i] = static_cast<float>((i * 2654435761u) % 255) - 127.5f;
  };
  dwt::DwtParams p;
  p.kernel = dwt::KernelId::Irreversible97;
  p.levels = 5;
  auto timed = [&](dwt::DwtBackend& backend) {
    refill();
    const auto t0 = Clock::now();
    backend.forward(dwt::make_span(plane.data(), kSide, kSide), p);
    return ms_since(t0);
  };
  const double cpu_first = timed(cpu), cpu_second = timed(cpu);
  const double gpu_first = timed(gpu), gpu_second = timed(gpu);
  DwtCosts costs;
  costs.cpu_ns_per_sample = std::min(cpu_first, cpu_second) * 1e6 / kSamples;
  costs.gpu_ns_per_sample = gpu_second * 1e6 / kSamples;
  costs.gpu_setup_ms = gpu_compile_ms + std::max(0.0, gpu_first - gpu_second);
  return costs;
}

std::optional<std::filesystem::path> dwt_cost_cache_path() {
  auto env = [](const char* name) -> std::optional<std::string> {
    const char* v = std::getenv(name);
    if (v == nullptr || *v == '\0') return std::nullopt;
    return std::string(v);
  };
  std::filesystem::path dir;
  if (auto d = env("GPUJ2K_CACHE_DIR"))
    dir = *d;
  else if (auto x = env("XDG_CACHE_HOME"))
    dir = std::filesystem::path(*x) / "gpuj2k";
  else if (auto h = env("HOME"))
    dir = std::filesystem::path(*h) / ".cache" / "gpuj2k";
  else
    return std::nullopt;
  return dir / "dwt-costs.tsv";
}

std::optional<DwtCosts> load_dwt_costs(const std::filesystem::path& cache, const std::string& key) {
  std::ifstream in(cache);
  std::string line;
  const std::string wanted = clean_key(key);
  while (std::getline(in, line)) {
    const auto tab = line.find('\t');
    if (tab == std::string::npos || line.compare(0, tab, wanted) != 0 || tab != wanted.size()) continue;
    std::istringstream fields(line.substr(tab + 1));
    DwtCosts c;
    if (fields >> c.cpu_ns_per_sample >> c.gpu_setup_ms >> c.gpu_ns_per_sample && c.cpu_ns_per_sample > 0 &&
        c.gpu_ns_per_sample > 0 && c.gpu_setup_ms >= 0)
      return c;
  }
  return std::nullopt;
}

void store_dwt_costs(const std::filesystem::path& cache, const std::string& key, const DwtCosts& costs) {
  std::error_code ec;
  std::filesystem::create_directories(cache.parent_path(), ec);
  std::vector<std::string> kept;
  const std::string k = clean_key(key);
  {
    std::ifstream in(cache);
    std::string line;
    while (std::getline(in, line))
      if (line.compare(0, k.size() + 1, k + '\t') != 0) kept.push_back(line);
  }
  kept.push_back(k + '\t' + std::to_string(costs.cpu_ns_per_sample) + '\t' + std::to_string(costs.gpu_setup_ms) + '\t' +
                 std::to_string(costs.gpu_ns_per_sample));
  std::filesystem::path temporary = cache;
  temporary += ".tmp" + std::to_string(static_cast<long long>(Clock::now().time_since_epoch().count()));
  {
    std::ofstream out(temporary);
    for (const std::string& line : kept) out << line << '\n';
    if (!out) {
      std::filesystem::remove(temporary, ec);
      return;
    }
  }
  std::filesystem::rename(temporary, cache, ec);
  if (ec) std::filesystem::remove(temporary, ec);
}

namespace {

// A GL context with the DWT shader compiled, made for one encode or for an engine, or why none.
struct MadeGpu {
  std::unique_ptr<dwt_gpu::GpuBackend> gpu;
  std::string failure;
  double context_ms = 0, compile_ms = 0, calibration_ms = 0;
  std::optional<DwtCosts> costs;  // hardware: the calibration against the CPU lifting
  bool costs_measured_now = false;
};

// --dwt gpu: any renderer, software ones included.
MadeGpu make_any_gpu() {
  MadeGpu made;
  try {
    made.gpu = std::make_unique<dwt_gpu::GpuBackend>(glc::Platform::Auto, true);
    made.context_ms = made.gpu->last_timings().context_ms;
    made.compile_ms = made.gpu->last_timings().compile_ms;
  } catch (const std::exception& e) {
    made.failure = e.what();
  }
  return made;
}

// --dwt auto: a hardware GPU only, with its costs from the cache or measured now against `cpu`.
MadeGpu make_hardware_gpu(dwt::DwtBackend& cpu) {
  MadeGpu made;
  const auto t0 = Clock::now();
  std::unique_ptr<glc::Context> context;
  try {
    context = glc::Context::create_hardware();
  } catch (const std::exception& e) {
    made.failure = e.what();
    return made;
  }
  made.context_ms = ms_since(t0);
  const std::string renderer = context->description();
  const auto compile_start = Clock::now();
  made.gpu = std::make_unique<dwt_gpu::GpuBackend>(std::move(context));
  made.compile_ms = ms_since(compile_start);
  const std::string key = renderer + " | " + cpu.name();
  const auto cache = dwt_cost_cache_path();
  made.costs = cache ? load_dwt_costs(*cache, key) : std::nullopt;
  made.costs_measured_now = !made.costs;
  if (!made.costs) {
    const auto calibration_start = Clock::now();
    made.costs = calibrate_dwt(cpu, *made.gpu, made.compile_ms);
    made.calibration_ms = ms_since(calibration_start);
    if (cache) store_dwt_costs(*cache, key, *made.costs);
  }
  return made;
}

std::string gpu_name(const std::string& renderer) { return "gpu fragment shaders (" + renderer + ")"; }

}  // namespace

EncodeEngine::~EncodeEngine() = default;

const EncodeEngine::Gpu& EncodeEngine::gpu(bool hardware, const std::function<Gpu()>& make, bool& made_now) {
  std::lock_guard lock(mutex_);
  std::optional<Gpu>& slot = hardware ? hardware_ : any_;
  made_now = !slot;
  if (!slot) slot = make();
  return *slot;
}

DwtChoice choose_dwt(const EncodeParams& params, double samples, base::ThreadPool& pool) {
  DwtChoice choice;
  auto cpu = std::make_unique<dwt_cpu::CpuBackend>(pool);
  auto use_cpu = [&](std::string reason) {
    choice.name = cpu->name();
    choice.backend = std::move(cpu);
    choice.reason = std::move(reason);
    return std::move(choice);
  };
  if (params.lossless) return use_cpu("lossless: the reversible 5/3 runs on the CPU");
  if (params.dwt == DwtDevice::Cpu) return use_cpu("asked for the CPU");
  const bool hardware = params.dwt == DwtDevice::Auto;

  // The GPU: this encode's own, or the engine's (made by whichever encode asked first, which
  // reports its costs; the others find it ready).
  std::unique_ptr<dwt::DwtBackend> gpu;
  std::string renderer, failure;
  std::optional<DwtCosts> costs;
  bool measured_now = false;
  auto take_times = [&](const MadeGpu& made) {
    choice.gl_context_ms = made.context_ms;
    choice.shader_compile_ms = made.compile_ms;
    choice.calibration_ms = made.calibration_ms;
    measured_now = made.costs_measured_now;
  };
  if (params.engine) {
    bool made_now = false;
    const EncodeEngine::Gpu& shared = params.engine->gpu(
        hardware,
        [&] {
          MadeGpu made = hardware ? make_hardware_gpu(*cpu) : make_any_gpu();
          take_times(made);
          EncodeEngine::Gpu kept;
          kept.failure = made.failure;
          kept.costs = made.costs;
          if (made.gpu) kept.gpu = std::make_shared<dwt_gpu::SharedGpu>(std::move(made.gpu));
          return kept;
        },
        made_now);
    failure = shared.failure;
    costs = shared.costs;
    if (shared.gpu) {
      renderer = shared.gpu->renderer();
      gpu = std::make_unique<dwt_gpu::SharedGpuUser>(shared.gpu);
    }
  } else {
    MadeGpu made = hardware ? make_hardware_gpu(*cpu) : make_any_gpu();
    take_times(made);
    failure = made.failure;
    costs = made.costs;
    if (made.gpu) {
      renderer = made.gpu->renderer();
      gpu = std::move(made.gpu);
    }
  }

  if (!hardware) {
    if (!gpu) throw EncodeError("the GPU DWT was asked for and no GL context could be made: " + failure);
    choice.name = gpu_name(renderer);
    choice.backend = std::move(gpu);
    choice.reason = "asked for the GPU";
    return choice;
  }
  // Auto: a hardware GPU, and only where it is faster.
  if (!gpu) return use_cpu(failure + "; the 9/7 runs on the CPU");
  const double gpu_ms = costs->gpu_setup_ms + costs->gpu_ns_per_sample * samples * 1e-6;
  const double cpu_ms = costs->cpu_ns_per_sample * samples * 1e-6;
  const std::string prediction = "predicted " + fixed(gpu_ms, 1) + " ms on " + renderer + " against " +
                                 fixed(cpu_ms, 1) + " ms on the CPU (costs " +
                                 (measured_now ? "measured now" : "from the cache") + ")";
  if (gpu_pays_off(*costs, samples)) {
    choice.name = gpu_name(renderer);
    choice.backend = std::move(gpu);
    choice.reason = "the GPU is faster here: " + prediction;
    return choice;
  }
  return use_cpu("the CPU is faster here: " + prediction);
}

}  // namespace codec
