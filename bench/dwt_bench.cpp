// DWT benchmark (not a test): forward and inverse 9/7, 5 levels, on square single-component planes,
// CPU lifting vs the GPU fragment-shader method side by side in one run, with the GPU's time split
// like the thesis' Table 4.1 (context creation, shader compilation, upload, compute, download).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "bench_images.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

struct Row {
  int size;
  std::string source;
  double cpu_fwd, cpu_inv;
  double gpu_upload, gpu_fwd, gpu_inv, gpu_download;
  bool gpu = false;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"DWT benchmark: CPU lifting vs GPU fragment shaders, 9/7, forward and inverse"};
  std::vector<int> sizes = {512, 1024, 2048, 4096};
  int reps = 5, threads = 0, levels = 5;
  std::string gl = "auto", csv;
  bool no_gpu = false;
  app.add_option("--sizes", sizes, "square plane sizes")->delimiter(',');
  app.add_option("--reps", reps, "repetitions per measurement (median reported)")->check(CLI::PositiveNumber);
  app.add_option("--threads", threads, "CPU threads (0: all hardware threads)");
  app.add_option("--levels", levels, "decomposition levels");
  app.add_option("--gl", gl, "GL platform: auto, egl-device, egl-surfaceless, osmesa");
  app.add_option("--csv", csv, "also write the table as CSV to this file");
  app.add_flag("--no-gpu", no_gpu, "CPU only");
  CLI11_PARSE(app, argc, argv);

  try {
    dwt_cpu::CpuBackend cpu(threads);
    std::unique_ptr<dwt_gpu::GpuBackend> gpu;
    std::string renderer = "none";
    double context_ms = 0, compile_ms = 0;
    if (!no_gpu) {
      gpu = std::make_unique<dwt_gpu::GpuBackend>(glc::parse_platform(gl), true);
      context_ms = gpu->last_timings().context_ms;
      compile_ms = gpu->last_timings().compile_ms;
      renderer = gpu->renderer();
    }
    const std::string kodak = bench::find_kodak_dir();
    std::printf("# DWT benchmark: 9/7, %d levels, whole-sample symmetric, float32, forward and inverse\n", levels);
    std::printf("CPU: %s on %s (%u hardware threads)\n", cpu.name().c_str(), cpu_model().c_str(),
                std::thread::hardware_concurrency());
    std::printf("GPU: %s\n", renderer.c_str());
    if (gpu)
      std::printf("GPU one-time costs: context creation %.1f ms, shader compilation %.1f ms\n", context_ms, compile_ms);
    std::printf("Median of %d runs. GPU total = upload + compute + download of one transform.\n\n", reps);
    std::printf(
        "| size | content | CPU fwd ms | CPU inv ms | CPU fwd MS/s | GPU upload ms | GPU fwd compute ms | GPU inv "
        "compute ms | GPU download ms | GPU fwd total ms | GPU fwd MS/s | CPU/GPU fwd total |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");

    std::vector<Row> rows;
    const dwt::DwtParams params{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, levels, {0, 0}};
    for (int size : sizes) {
      const bench::BenchPlane plane = bench::make_plane(size, kodak);
      Row r{size, plane.source, 0, 0, 0, 0, 0, 0};
      std::vector<double> fwd, inv;
      std::vector<float> work;
      for (int i = 0; i < reps; ++i) {
        work = plane.samples;
        auto t0 = Clock::now();
        cpu.forward(dwt::make_span(work.data(), size, size), params);
        auto t1 = Clock::now();
        cpu.inverse(dwt::make_span(work.data(), size, size), params);
        auto t2 = Clock::now();
        fwd.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        inv.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
      }
      r.cpu_fwd = median(fwd);
      r.cpu_inv = median(inv);
      if (gpu) {
        r.gpu = true;
        std::vector<double> up, comp, icomp, down;
        work = plane.samples;
        gpu->forward(dwt::make_span(work.data(), size, size), params);  // warm-up: allocates the textures
        for (int i = 0; i < reps; ++i) {
          work = plane.samples;
          gpu->forward(dwt::make_span(work.data(), size, size), params);
          const auto t = gpu->last_timings();
          up.push_back(t.upload_ms);
          comp.push_back(t.compute_ms);
          down.push_back(t.download_ms);
          gpu->inverse(dwt::make_span(work.data(), size, size), params);
          icomp.push_back(gpu->last_timings().compute_ms);
        }
        r.gpu_upload = median(up);
        r.gpu_fwd = median(comp);
        r.gpu_inv = median(icomp);
        r.gpu_download = median(down);
      }
      const double msamples = double(size) * size / 1e6;
      const double gpu_total = r.gpu_upload + r.gpu_fwd + r.gpu_download;
      std::printf("| %d² | %s | %.2f | %.2f | %.1f |", size, r.source.c_str(), r.cpu_fwd, r.cpu_inv,
                  msamples / (r.cpu_fwd / 1e3));
      if (r.gpu)
        std::printf(" %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f |\n", r.gpu_upload, r.gpu_fwd, r.gpu_inv,
                    r.gpu_download, gpu_total, msamples / (gpu_total / 1e3), r.cpu_fwd / gpu_total);
      else
        std::printf(" - | - | - | - | - | - | - |\n");
      std::fflush(stdout);
      rows.push_back(r);
    }
    if (!csv.empty()) {
      std::ofstream out(csv);
      out << "size,cpu_threads,renderer,cpu_fwd_ms,cpu_inv_ms,gpu_context_ms,gpu_compile_ms,gpu_upload_ms,gpu_fwd_ms,"
             "gpu_inv_ms,gpu_download_ms\n";
      for (const Row& r : rows)
        out << r.size << "," << cpu.threads() << ",\"" << renderer << "\"," << r.cpu_fwd << "," << r.cpu_inv << ","
            << context_ms << "," << compile_ms << "," << r.gpu_upload << "," << r.gpu_fwd << "," << r.gpu_inv << ","
            << r.gpu_download << "\n";
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dwt_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
