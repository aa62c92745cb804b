#include "codec/encoder/dwt_choice.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

#include "codec/structure/error.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"
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

DwtChoice choose_dwt(const EncodeParams& params, double samples, base::ThreadPool& pool) {
  DwtChoice choice;
  auto use_cpu = [&](std::string reason) {
    auto cpu = std::make_unique<dwt_cpu::CpuBackend>(pool);
    choice.name = cpu->name();
    choice.backend = std::move(cpu);
    choice.reason = std::move(reason);
    return std::move(choice);
  };
  if (params.lossless) return use_cpu("lossless: the reversible 5/3 runs on the CPU");
  if (params.dwt == DwtDevice::Cpu) return use_cpu("asked for the CPU");

  if (params.dwt == DwtDevice::Gpu) {
    try {
      auto gpu = std::make_unique<dwt_gpu::GpuBackend>(glc::Platform::Auto, true);
      choice.name = "gpu fragment shaders (" + gpu->renderer() + ")";
      choice.gl_context_ms = gpu->last_timings().context_ms;
      choice.shader_compile_ms = gpu->last_timings().compile_ms;
      choice.backend = std::move(gpu);
      choice.reason = "asked for the GPU";
      return choice;
    } catch (const std::exception& e) {
      throw EncodeError(std::string("the GPU DWT was asked for and no GL context could be made: ") + e.what());
    }
  }

  // Auto: a hardware GPU, and only where it is faster.
  const auto t0 = Clock::now();
  std::unique_ptr<glc::Context> context;
  try {
    context = glc::Context::create_hardware();
  } catch (const std::exception& e) {
    return use_cpu(std::string(e.what()) + "; the 9/7 runs on the CPU");
  }
  choice.gl_context_ms = ms_since(t0);
  const std::string renderer = context->description();
  const auto compile_start = Clock::now();
  auto gpu = std::make_unique<dwt_gpu::GpuBackend>(std::move(context));
  choice.shader_compile_ms = ms_since(compile_start);
  auto cpu = std::make_unique<dwt_cpu::CpuBackend>(pool);
  const std::string key = renderer + " | " + cpu->name();
  const auto cache = dwt_cost_cache_path();
  std::optional<DwtCosts> costs = cache ? load_dwt_costs(*cache, key) : std::nullopt;
  const bool measured_now = !costs;
  if (!costs) {
    const auto calibration_start = Clock::now();
    costs = calibrate_dwt(*cpu, *gpu, choice.shader_compile_ms);
    choice.calibration_ms = ms_since(calibration_start);
    if (cache) store_dwt_costs(*cache, key, *costs);
  }
  const double gpu_ms = costs->gpu_setup_ms + costs->gpu_ns_per_sample * samples * 1e-6;
  const double cpu_ms = costs->cpu_ns_per_sample * samples * 1e-6;
  const std::string prediction = "predicted " + fixed(gpu_ms, 1) + " ms on " + renderer + " against " + fixed(cpu_ms, 1) +
                                 " ms on the CPU (costs " + (measured_now ? "measured now" : "from the cache") + ")";
  if (gpu_pays_off(*costs, samples)) {
    choice.name = "gpu fragment shaders (" + renderer + ")";
    choice.backend = std::move(gpu);
    choice.reason = "the GPU is faster here: " + prediction;
    return choice;
  }
  choice.name = cpu->name();
  choice.backend = std::move(cpu);
  choice.reason = "the CPU is faster here: " + prediction;
  return choice;
}

}  // namespace codec
