// --dwt auto (codec/encoder/dwt_choice.h): never a software rasteriser, the GPU only where its
// measured costs beat the CPU's, and a cost cache that survives damage.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "codec/encoder/dwt_choice.h"
#include "codec/encoder/encoder.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/gpu_backend.h"
#include "glcontext/context.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"

namespace {

namespace fs = std::filesystem;

TEST(DwtChoice, SoftwareRenderersAreRecognised) {
  EXPECT_TRUE(glc::is_software_renderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(glc::is_software_renderer("softpipe"));
  EXPECT_TRUE(glc::is_software_renderer("Mesa X11 swrast"));
  EXPECT_TRUE(glc::is_software_renderer("SwiftShader Device (Subzero)"));
  EXPECT_FALSE(glc::is_software_renderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"));
  EXPECT_FALSE(glc::is_software_renderer("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7, DRM 3.54)"));
}

TEST(DwtChoice, GpuOnlyWhereItsCostsBeatTheCpu) {
  const codec::DwtCosts costs{10.0, 50.0, 1.0, ""};  // CPU 10 ns per sample; GPU 50 ms once, then 1 ns
  // Crossover: 50 ms / 9 ns = 5.56 million samples.
  EXPECT_FALSE(codec::gpu_pays_off(costs, 1e6));
  EXPECT_FALSE(codec::gpu_pays_off(costs, 5.5e6));
  EXPECT_TRUE(codec::gpu_pays_off(costs, 5.6e6));
  EXPECT_FALSE(codec::gpu_pays_off(codec::DwtCosts{1.0, 0.0, 2.0, ""}, 1e9));  // a GPU slower per sample never wins
}

TEST(DwtChoice, CostCacheRoundTripsAndSurvivesDamage) {
  test_support::ScratchDir s;
  const fs::path cache = s / "sub" / "dwt-costs.tsv";
  EXPECT_FALSE(codec::load_dwt_costs(cache, "gpu a").has_value());
  codec::store_dwt_costs(cache, "gpu a", {3.5, 40.25, 0.75, ""});
  codec::store_dwt_costs(cache, "gpu b", {2.0, 10.0, 1.5, ""});
  codec::store_dwt_costs(cache, "gpu a", {4.0, 41.0, 0.5, ""});  // replaces the first line for "gpu a"
  const auto a = codec::load_dwt_costs(cache, "gpu a");
  ASSERT_TRUE(a.has_value());
  EXPECT_DOUBLE_EQ(a->cpu_ns_per_sample, 4.0);
  EXPECT_DOUBLE_EQ(a->gpu_setup_ms, 41.0);
  EXPECT_DOUBLE_EQ(a->gpu_ns_per_sample, 0.5);
  ASSERT_TRUE(codec::load_dwt_costs(cache, "gpu b").has_value());
  EXPECT_FALSE(codec::load_dwt_costs(cache, "gpu").has_value());  // keys match whole
  {
    std::ofstream damaged(cache, std::ios::app);
    damaged << "gpu c\tnot numbers\n\x01\x02 garbage without a tab\ngpu d\t-1\t5\t1\n";
  }
  EXPECT_FALSE(codec::load_dwt_costs(cache, "gpu c").has_value());
  EXPECT_FALSE(codec::load_dwt_costs(cache, "gpu d").has_value());  // negative costs are refused
  ASSERT_TRUE(codec::load_dwt_costs(cache, "gpu a").has_value());
  codec::store_dwt_costs(fs::path("/proc/no-such-dir/x.tsv"), "k", {1, 1, 1, ""});  // best effort: no throw
}

// The renderer the costs were measured on travels with them (the reports name it), and a line
// written before it did still loads.
TEST(DwtChoice, CostCacheKeepsTheRenderer) {
  test_support::ScratchDir s;
  const fs::path cache = s / "dwt-costs.tsv";
  const std::string renderer = "NVIDIA H200/PCIe/SSE2 | 3.3.0 NVIDIA 580.159.04 | egl-device";
  codec::store_dwt_costs(cache, "gpus | cpu", {1.1, 4.5, 6.2, renderer});
  const auto costs = codec::load_dwt_costs(cache, "gpus | cpu");
  ASSERT_TRUE(costs.has_value());
  EXPECT_EQ(costs->renderer, renderer);
  {
    std::ofstream older(cache, std::ios::app);
    older << "older | cpu\t1.5\t3.5\t5.7\n";
  }
  const auto older = codec::load_dwt_costs(cache, "older | cpu");
  ASSERT_TRUE(older.has_value());
  EXPECT_DOUBLE_EQ(older->gpu_ns_per_sample, 5.7);
  EXPECT_FALSE(older->renderer.empty());
}

// --dwt auto decides from the cache before making a GL context where the cache gives the image to
// the CPU; without costs, or where the GPU would win, the context is made as before.
TEST(DwtChoice, CachedCostsGiveTheCpuItsImagesWithoutAContext) {
  test_support::ScratchDir s;
  const fs::path cache = s / "dwt-costs.tsv";
  const std::string key = codec::dwt_cost_key("nvidia 580.159.04: NVIDIA H200", "cpu lifting (AVX3, 16 threads)");
  EXPECT_FALSE(codec::cpu_wins_by_cached_costs(cache, key, 4e6).has_value());         // nothing cached yet
  EXPECT_FALSE(codec::cpu_wins_by_cached_costs(std::nullopt, key, 4e6).has_value());  // no cache at all
  codec::store_dwt_costs(cache, key, {1.0, 50.0, 0.5, "NVIDIA H200"});  // GPU: 50 ms once, then half the CPU's cost
  const auto small = codec::cpu_wins_by_cached_costs(cache, key, 4e6);  // CPU 4 ms against 52 ms
  ASSERT_TRUE(small.has_value());
  EXPECT_NE(small->find("the CPU is faster here"), std::string::npos) << *small;
  EXPECT_NE(small->find("NVIDIA H200"), std::string::npos) << *small;
  EXPECT_NE(small->find("no GL context"), std::string::npos) << *small;
  EXPECT_FALSE(codec::cpu_wins_by_cached_costs(cache, key, 4e8).has_value());  // 400 ms against 250 ms: the GPU
  EXPECT_FALSE(
      codec::cpu_wins_by_cached_costs(cache, codec::dwt_cost_key("other GPUs", "cpu lifting (AVX3, 16 threads)"), 4e6)
          .has_value());
}

// The calibration runs on whatever context there is (llvmpipe in CI): positive, finite costs.
TEST(DwtChoice, CalibrationMeasuresBothSides) {
  std::unique_ptr<dwt_gpu::GpuBackend> gpu;
  try {
    gpu = std::make_unique<dwt_gpu::GpuBackend>(glc::Platform::Auto, true);
  } catch (const std::exception& e) {
    GTEST_SKIP() << "no GL context at all: " << e.what();
  }
  dwt_cpu::CpuBackend cpu(1);
  const codec::DwtCosts c = codec::calibrate_dwt(cpu, *gpu, gpu->last_timings().compile_ms);
  std::printf("%s: CPU %.2f ns/sample, GPU %.1f ms + %.2f ns/sample\n", gpu->renderer().c_str(), c.cpu_ns_per_sample,
              c.gpu_setup_ms, c.gpu_ns_per_sample);
  EXPECT_GT(c.cpu_ns_per_sample, 0.0);
  EXPECT_GT(c.gpu_ns_per_sample, 0.0);
  EXPECT_GE(c.gpu_setup_ms, gpu->last_timings().compile_ms);
  EXPECT_LT(c.cpu_ns_per_sample, 1e4);
}

// What a user without a GPU gets by default: the CPU, the reason said, the same file as --dwt cpu.
// On a machine with a hardware GPU the choice may differ, but never a software renderer.
TEST(DwtChoice, AutoNeverRunsOnASoftwareRasteriser) {
  test_support::ScratchDir s;
  ::setenv("GPUJ2K_CACHE_DIR", s.path().c_str(), 1);
  const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 192, 128, 3, 8);
  const codec::SourceImage source = codec::to_source_image(img, "image");
  codec::EncodeParams p;
  p.lossless = false;
  p.layers.push_back({codec::LayerTarget::Kind::Bytes, 192 * 128 * 0.75 / 8});
  p.dwt = codec::DwtDevice::Cpu;
  const auto cpu = codec::encode(source, p, codec::FileFormat::Codestream);
  p.dwt = codec::DwtDevice::Auto;
  codec::EncodeReport report;
  const auto automatic = codec::encode(source, p, codec::FileFormat::Codestream, &report);
  std::printf("auto: %s (%s)\n", report.dwt_backend.c_str(), report.dwt_reason.c_str());
  EXPECT_FALSE(glc::is_software_renderer(report.dwt_backend)) << report.dwt_backend;
  EXPECT_FALSE(report.dwt_reason.empty());
  if (report.dwt_backend.rfind("cpu", 0) == 0) {
    EXPECT_EQ(automatic, cpu);
  }
  ::unsetenv("GPUJ2K_CACHE_DIR");
}

}  // namespace
