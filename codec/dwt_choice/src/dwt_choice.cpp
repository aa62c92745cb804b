#include "codec/dwt_choice/dwt_choice.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"
#include "glcontext/context.h"
#include "glcontext/gpu_fingerprint.h"

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
        c.gpu_ns_per_sample > 0 && c.gpu_setup_ms >= 0) {
      std::getline(fields >> std::ws, c.renderer);
      if (c.renderer.empty()) c.renderer = "the cached GPU";
      return c;
    }
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
                 std::to_string(costs.gpu_ns_per_sample) + '\t' + clean_key(costs.renderer));
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

std::string dwt_cost_key(const std::string& gpu_fingerprint, const std::string& cpu_name) {
  return gpu_fingerprint + " | " + cpu_name;
}

namespace {

std::string prediction(const DwtCosts& costs, double samples, bool measured_now) {
  const double gpu_ms = costs.gpu_setup_ms + costs.gpu_ns_per_sample * samples * 1e-6;
  const double cpu_ms = costs.cpu_ns_per_sample * samples * 1e-6;
  return "predicted " + fixed(gpu_ms, 1) + " ms on " + costs.renderer + " against " + fixed(cpu_ms, 1) +
         " ms on the CPU (costs " + (measured_now ? "measured now" : "from the cache") + ")";
}

}  // namespace

std::optional<std::string> cpu_wins_by_cached_costs(const std::optional<std::filesystem::path>& cache,
                                                    const std::string& key, double samples) {
  if (!cache) return std::nullopt;
  const std::optional<DwtCosts> costs = load_dwt_costs(*cache, key);
  if (!costs || gpu_pays_off(*costs, samples)) return std::nullopt;
  return "the CPU is faster here: " + prediction(*costs, samples, false) + ", so no GL context was made";
}

std::optional<std::string> cpu_wins_here_by_cached_costs(const std::string& cpu_name, double samples) {
  const std::string gpus = glc::hardware_gpu_fingerprint();
  if (gpus.empty()) return std::nullopt;
  return cpu_wins_by_cached_costs(dwt_cost_cache_path(), dwt_cost_key(gpus, cpu_name), samples);
}

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
  const std::string key = dwt_cost_key(glc::hardware_gpu_fingerprint(), cpu.name());
  const auto cache = dwt_cost_cache_path();
  made.costs = cache ? load_dwt_costs(*cache, key) : std::nullopt;
  made.costs_measured_now = !made.costs;
  if (!made.costs) {
    const auto calibration_start = Clock::now();
    made.costs = calibrate_dwt(cpu, *made.gpu, made.compile_ms);
    made.costs->renderer = renderer;
    made.calibration_ms = ms_since(calibration_start);
    if (cache) store_dwt_costs(*cache, key, *made.costs);
  }
  return made;
}

namespace {

std::string gpu_name(const std::string& renderer) { return "gpu fragment shaders (" + renderer + ")"; }

DwtChoice gpu_choice(GpuCandidate& candidate, std::string reason) {
  DwtChoice choice;
  choice.name = gpu_name(candidate.renderer);
  choice.backend = std::move(candidate.backend);
  choice.reason = std::move(reason);
  return choice;
}

}  // namespace

DwtChoice cpu_choice(std::unique_ptr<dwt::DwtBackend> cpu, std::string reason) {
  DwtChoice choice;
  choice.name = cpu->name();
  choice.backend = std::move(cpu);
  choice.reason = std::move(reason);
  return choice;
}

DwtChoice settle_dwt(DwtDevice device, GpuCandidate candidate, std::unique_ptr<dwt::DwtBackend> cpu, double samples) {
  if (device == DwtDevice::Cpu) return cpu_choice(std::move(cpu), "asked for the CPU");
  if (device == DwtDevice::Gpu) {
    if (!candidate.backend) {
      DwtChoice none;
      none.reason = "the GPU DWT was asked for and no GL context could be made: " + candidate.failure;
      return none;
    }
    return gpu_choice(candidate, "asked for the GPU");
  }
  // Auto: a hardware GPU, and only where it is faster.
  if (!candidate.backend || !candidate.costs)
    return cpu_choice(std::move(cpu), candidate.failure + "; the 9/7 runs on the CPU");
  DwtCosts costs = *candidate.costs;
  costs.renderer = candidate.renderer;
  const std::string predicted = prediction(costs, samples, candidate.costs_measured_now);
  if (gpu_pays_off(costs, samples)) return gpu_choice(candidate, "the GPU is faster here: " + predicted);
  return cpu_choice(std::move(cpu), "the CPU is faster here: " + predicted);
}

DwtChoice choose_dwt(DwtDevice device, double samples, base::ThreadPool& pool) {
  auto cpu = std::make_unique<dwt_cpu::CpuBackend>(pool);
  if (device == DwtDevice::Cpu) return cpu_choice(std::move(cpu), "asked for the CPU");
  if (device == DwtDevice::Auto)
    if (auto reason = cpu_wins_here_by_cached_costs(cpu->name(), samples))
      return cpu_choice(std::move(cpu), std::move(*reason));
  MadeGpu made = device == DwtDevice::Auto ? make_hardware_gpu(*cpu) : make_any_gpu();
  GpuCandidate candidate;
  candidate.failure = made.failure;
  candidate.costs = made.costs;
  candidate.costs_measured_now = made.costs_measured_now;
  if (made.gpu) {
    candidate.renderer = made.gpu->renderer();
    candidate.backend = std::move(made.gpu);
  }
  DwtChoice choice = settle_dwt(device, std::move(candidate), std::move(cpu), samples);
  choice.gl_context_ms = made.context_ms;
  choice.shader_compile_ms = made.compile_ms;
  choice.calibration_ms = made.calibration_ms;
  return choice;
}

}  // namespace codec
