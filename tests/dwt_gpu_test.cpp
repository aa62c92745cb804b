// The GPU backend (the thesis' fragment-shader method) against the CPU backend, its own round trips,
// and the indirect address table against the thesis' figure 4.5. These run on whatever context the
// GL layer makes: Mesa llvmpipe in CI, a real GPU where there is one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dwt/error.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_gpu/address_table.h"
#include "dwt_gpu/gpu_backend.h"
#include "dwt_test_matrix.h"

namespace {

using testmatrix::Shape;

// Made once and never destroyed. As a plain static it was destroyed by exit(), and on an NVIDIA H200
// (driver 580.159.04) its GL calls there jumped to an address no longer mapped: every test passed,
// then SIGSEGV (cuda-gdb: exit -> this destructor -> ??). GL objects do not belong in statics.
dwt_gpu::GpuBackend& gpu() {
  static dwt_gpu::GpuBackend& backend = *new dwt_gpu::GpuBackend;
  static const bool announced = [] {
    std::printf("GL renderer: %s\n", backend.renderer().c_str());
    return true;
  }();
  (void)announced;
  return backend;
}

dwt_cpu::CpuBackend& cpu() {
  static dwt_cpu::CpuBackend backend(2);
  return backend;
}

// Figure 4.5: a sequence of length 14, k = 5 (two extension texels each side), three levels of
// whole-sample symmetric extension.
TEST(AddressTable, ReproducesThesisFigure4_5) {
  const std::vector<std::vector<int>> printed = {
      {2, 1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 12, 11},
      {2, 1, 0, 1, 2, 3, 4, 5, 6, 5, 4},
      {2, 1, 0, 1, 2, 3, 2, 1},
  };
  const auto levels = dwt::decomposition(14, 1, {0, 0}, 3);
  for (int d = 0; d < 3; ++d) {
    const auto row = dwt_gpu::forward_row(levels[static_cast<std::size_t>(d)].x, 2, dwt::Boundary::Symmetric);
    ASSERT_EQ(row.size(), printed[static_cast<std::size_t>(d)].size()) << "level " << d;
    for (std::size_t i = 0; i < row.size(); ++i)
      EXPECT_EQ(row[i].address, printed[static_cast<std::size_t>(d)][i]) << "level " << d << " texel " << i;
  }
  // The table's width is L + k - 1 and it has one row per level and axis.
  const auto table = dwt_gpu::build_table(levels, 2, dwt::Boundary::Symmetric, false);
  EXPECT_EQ(table.width, 14 + 5 - 1);
  EXPECT_EQ(table.rows, 6);
}

TEST(AddressTable, FilterSelectorAndBasePositionFollowEquations4_11And4_12) {
  // Even origin, L = 7: four low-pass outputs centred on 0, 2, 4, 6; three high-pass on 1, 3, 5.
  const auto row = dwt_gpu::forward_row({0, 7}, 4, dwt::Boundary::Symmetric);
  const float alpha[] = {0, 0, 0, 0, 1, 1, 1}, beta[] = {0, 2, 4, 6, 1, 3, 5};
  for (int n = 0; n < 7; ++n) {
    EXPECT_EQ(row[static_cast<std::size_t>(n + 4)].alpha, alpha[n]);
    EXPECT_EQ(row[static_cast<std::size_t>(n + 4)].beta, beta[n]);
  }
  // Odd origin: the first sample is high-pass, so low-pass outputs centre on 1, 3, 5.
  const auto odd = dwt_gpu::forward_row({1, 7}, 4, dwt::Boundary::Symmetric);
  const float beta_odd[] = {1, 3, 5, 0, 2, 4, 6};
  for (int n = 0; n < 7; ++n) EXPECT_EQ(odd[static_cast<std::size_t>(n + 4)].beta, beta_odd[n]);
  // Inverse (figure 4.7): extended position -1 of an even-origin sequence mirrors to 1, a high-pass
  // position whose coefficient is the first high-pass one, Mallat index 4.
  const auto inv = dwt_gpu::inverse_row({0, 7}, 4, dwt::Boundary::Symmetric);
  EXPECT_EQ(inv[3].address, 4);
  EXPECT_EQ(inv[4].address, 0);
  EXPECT_EQ(inv[5].address, 4);
  EXPECT_EQ(inv[6].address, 1);
}

double max_abs_diff(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

const dwt::KernelId kFloatKernels[] = {dwt::KernelId::Irreversible97, dwt::KernelId::Float53, dwt::KernelId::Haar};
const dwt::Boundary kBoundaries[] = {dwt::Boundary::Symmetric, dwt::Boundary::Periodic, dwt::Boundary::Zero};

// GPU vs CPU over the matrix, forward and inverse, within 1e-4 of the dynamic range.
TEST(DwtGpu, AgreesWithCpuOnTheWholeMatrix) {
  const double tolerance = 1e-4 * 255;
  double worst_seen = 0;
  int configurations = 0;
  for (dwt::KernelId kid : kFloatKernels)
    for (dwt::Boundary b : kBoundaries)
      for (Shape s : testmatrix::shapes())
        for (dwt::Origin o : testmatrix::origins()) {
          // The largest shapes only at the maximal level count, to keep llvmpipe's share of CI small.
          const int most = dwt::max_levels(s.w, s.h, o);
          std::vector<int> level_counts = {most};
          if (most > 1 && std::max(s.w, s.h) <= 64) level_counts.push_back(1);
          for (int levels : level_counts) {
            const auto input = testmatrix::samples(s.w, s.h, static_cast<std::uint32_t>(s.w * 17 + s.h));
            const dwt::DwtParams p{kid, b, levels, o};
            const std::string what = testmatrix::describe(dwt::get_kernel(kid).name.data(), b, s, o, levels);
            auto on_cpu = input, on_gpu = input;
            cpu().forward(dwt::make_span(on_cpu.data(), s.w, s.h), p);
            gpu().forward(dwt::make_span(on_gpu.data(), s.w, s.h), p);
            double d = max_abs_diff(on_cpu, on_gpu);
            worst_seen = std::max(worst_seen, d);
            ASSERT_LE(d, tolerance) << "forward, " << what;

            // Inverse of the same coefficients on both.
            auto back_cpu = on_cpu, back_gpu = on_cpu;
            cpu().inverse(dwt::make_span(back_cpu.data(), s.w, s.h), p);
            gpu().inverse(dwt::make_span(back_gpu.data(), s.w, s.h), p);
            d = max_abs_diff(back_cpu, back_gpu);
            worst_seen = std::max(worst_seen, d);
            ASSERT_LE(d, tolerance) << "inverse, " << what;

            if (testmatrix::perfect_reconstruction(kid, b, s, o, levels)) {
              auto round = on_gpu;
              gpu().inverse(dwt::make_span(round.data(), s.w, s.h), p);
              ASSERT_LE(max_abs_diff(round, input), tolerance) << "GPU round trip, " << what;
            }
            ++configurations;
          }
        }
  std::printf("%d configurations, largest GPU/CPU difference %.3g (tolerance %.3g)\n", configurations, worst_seen,
              tolerance);
}

TEST(DwtGpu, RoundTrip97OnAPhotographSizedPlane) {
  const Shape s{768, 512};
  const auto input = testmatrix::samples(s.w, s.h, 11);
  auto plane = input;
  const dwt::DwtParams p{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 5, {0, 0}};
  gpu().forward(dwt::make_span(plane.data(), s.w, s.h), p);
  const auto& t = gpu().last_timings();
  EXPECT_GT(t.compute_ms, 0.0);
  gpu().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
  EXPECT_LE(max_abs_diff(plane, input), 1e-4 * 255);
}

TEST(DwtGpu, StridedPlane) {
  const int w = 37, h = 23, stride = 41;
  std::vector<float> buffer(static_cast<std::size_t>(stride * h), -7.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      buffer[static_cast<std::size_t>(y * stride + x)] = static_cast<float>((x * 13 + y * 7) % 41);
  auto on_cpu = buffer;
  const dwt::DwtParams p{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 3, {1, 0}};
  gpu().forward(dwt::PlaneSpan<float>{buffer.data(), w, h, stride}, p);
  cpu().forward(dwt::PlaneSpan<float>{on_cpu.data(), w, h, stride}, p);
  EXPECT_LE(max_abs_diff(buffer, on_cpu), 1e-4 * 255);
  for (int y = 0; y < h; ++y)
    for (int x = w; x < stride; ++x) ASSERT_EQ(buffer[static_cast<std::size_t>(y * stride + x)], -7.0f);
}

TEST(DwtGpu, RefusesTheReversibleKernel) {
  std::vector<std::int32_t> ints(16);
  std::vector<float> floats(16);
  EXPECT_FALSE(gpu().supports(dwt::KernelId::Reversible53));
  EXPECT_TRUE(gpu().supports(dwt::KernelId::Irreversible97));
  EXPECT_THROW(
      gpu().forward(dwt::make_span(ints.data(), 4, 4), {dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, 1, {}}),
      dwt::DwtError);
  EXPECT_THROW(gpu().forward(dwt::make_span(floats.data(), 4, 4),
                             {dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, 1, {}}),
               dwt::DwtError);
  EXPECT_THROW(gpu().forward(dwt::make_span(floats.data(), 4, 4),
                             {dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 3, {}}),
               dwt::DwtError);
}

}  // namespace
