// wavelet_apps_bench: milliseconds per subband edit (forward 9/7 DWT, band operation, inverse; thesis
// 4.7's interactive loop) on square greyscale planes, on each backend, and what that means in frames
// per second. On the GPU the coefficients stay in textures from upload to read-back; the time
// counts upload, the passes and the read-back, not the one-time context creation. Every line names
// the renderer or CPU and the threads; a software renderer (llvmpipe) is said to be one.
//
//   wavelet_apps_bench [--sizes 512,1024,2048,4096] [--reps 3] [--threads 0] [--backends cpu,gpu]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_images.h"
#include "glcontext/context.h"
#include "wavelet_apps/band_spec.h"
#include "wavelet_apps/engine.h"

namespace wa = wavelet_apps;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {512, 1024, 2048, 4096};
  std::vector<std::string> backends = {"cpu", "gpu"};
  int reps = 3, threads = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--sizes") {
      sizes.clear();
      for (const auto& s : split(value)) sizes.push_back(std::stoi(s));
    } else if (key == "--reps") {
      reps = std::max(1, std::stoi(value));
    } else if (key == "--threads") {
      threads = std::stoi(value);
    } else if (key == "--backends") {
      backends = split(value);
    } else {
      std::fprintf(stderr, "wavelet_apps_bench: unknown option %s\n", key.c_str());
      return 2;
    }
  }
  const std::string kodak = bench::find_kodak_dir();
  std::printf(
      "# edit = forward 9/7 DWT (5 levels) + band operation (Y:1:*=1.8, Y:2:HH=0) + inverse, one plane;\n"
      "# an RGB or YCbCr edit is three planes. Median of %d runs after one warm-up.\n",
      reps);
  std::printf("%-8s %-6s %12s %10s  %s\n", "size", "backend", "ms/edit", "edits/s", "device");
  try {
    for (const std::string& backend : backends) {
      const wa::EngineKind kind = wa::parse_engine_kind(backend);
      auto engine = wa::make_engine(kind, threads, glc::platform_from_env());
      std::string device = engine->prepare();
      if (kind == wa::EngineKind::Gpu) {
        device = "renderer " + device;
        if (glc::is_software_renderer(device)) device += " [software rasteriser on the CPU, not a GPU]";
      }
      device +=
          " on " + cpu_model() + " (" + std::to_string(std::thread::hardware_concurrency()) + " hardware threads)";
      for (const int size : sizes) {
        const bench::BenchPlane source = bench::make_plane(size, kodak);
        dwt::DwtParams params;
        params.levels = 5;
        const std::vector<std::string> names = {"Y"};
        const std::vector<wa::ScaleSpec> specs = {wa::parse_scale_spec("Y:1:*=1.8", names, 5),
                                                  wa::parse_scale_spec("Y:2:HH=0", names, 5)};
        const auto ops = wa::scale_operations(specs, 0, size, size, params);
        std::vector<float> plane;
        std::vector<double> times;
        for (int r = 0; r <= reps; ++r) {
          plane = source.samples;
          const auto t0 = std::chrono::steady_clock::now();
          engine->process(dwt::make_span(plane.data(), size, size), {}, params, ops);
          const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          if (r > 0) times.push_back(ms);  // the first run pays buffer allocation
        }
        std::sort(times.begin(), times.end());
        const double ms = times[times.size() / 2];
        std::printf("%4dx%-4d %-6s %12.2f %10.2f  %s\n", size, size, backend.c_str(), ms, 1000.0 / ms, device.c_str());
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wavelet_apps_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
