// Subband geometry: the one place that decides where bands lie and how long each level is.
#include <gtest/gtest.h>

#include "dwt/boundary.h"
#include "dwt/geometry.h"

namespace {

TEST(Geometry, LowCountsFollowCanvasParity) {
  // T.800 F.3.1: low-pass samples sit at even canvas coordinates.
  EXPECT_EQ((dwt::AxisSpan{0, 7}.low_count()), 4);
  EXPECT_EQ((dwt::AxisSpan{1, 7}.low_count()), 3);
  EXPECT_EQ((dwt::AxisSpan{1, 1}.low_count()), 0);
  EXPECT_EQ((dwt::AxisSpan{2, 1}.low_count()), 1);
  EXPECT_EQ((dwt::AxisSpan{3, 4}.low_count()), 2);
  EXPECT_EQ((dwt::AxisSpan{5, 0}.low_count()), 0);
  EXPECT_EQ((dwt::AxisSpan{5, 9}.low_half().start), 3);
}

TEST(Geometry, MaxLevelsStopsAtOneByOne) {
  EXPECT_EQ(dwt::max_levels(1, 1, {}), 0);
  EXPECT_EQ(dwt::max_levels(2, 1, {}), 1);
  EXPECT_EQ(dwt::max_levels(1000, 1000, {}), 10);
  EXPECT_EQ(dwt::max_levels(1024, 1024, {}), 10);
  EXPECT_EQ(dwt::max_levels(1025, 3, {}), 11);
  // An odd origin can leave a single high-pass sample, and the region then empties one level earlier.
  EXPECT_EQ(dwt::max_levels(2, 2, {1, 1}), 1);
}

TEST(Geometry, BandsTileThePlane) {
  const auto levels = dwt::decomposition(13, 7, {3, 2}, 3);
  ASSERT_EQ(levels.size(), 3u);
  long area = 0;
  for (int d = 1; d <= 3; ++d)
    for (auto o : {dwt::Orientation::HL, dwt::Orientation::LH, dwt::Orientation::HH}) {
      const auto r = dwt::band_rect(levels, d, o);
      area += static_cast<long>(r.width) * r.height;
    }
  const auto ll = dwt::band_rect(levels, 3, dwt::Orientation::LL);
  area += static_cast<long>(ll.width) * ll.height;
  EXPECT_EQ(area, 13 * 7);
  const auto hl1 = dwt::band_rect(levels, 1, dwt::Orientation::HL);
  EXPECT_EQ(hl1.x, 6);  // 13 samples from x=3: 6 low (4,6,...,14), 7 high
  EXPECT_EQ(hl1.width, 7);
}

TEST(Boundary, ExtensionSchemes) {
  using dwt::Boundary;
  // Whole-sample symmetric, n = 4: ... 2 1 | 0 1 2 3 | 2 1 0 1 ...
  const int expect_sym[] = {1, 2, 3, 2, 1, 0, 1, 2, 3, 2, 1, 0, 1};
  for (int i = -5; i <= 7; ++i) EXPECT_EQ(dwt::extend_index(i, 4, Boundary::Symmetric), expect_sym[i + 5]) << i;
  EXPECT_EQ(dwt::extend_index(-3, 1, Boundary::Symmetric), 0);
  EXPECT_EQ(dwt::extend_index(-1, 4, Boundary::Periodic), 3);
  EXPECT_EQ(dwt::extend_index(9, 4, Boundary::Periodic), 1);
  EXPECT_EQ(dwt::extend_index(4, 4, Boundary::Zero), -1);
  EXPECT_EQ(dwt::extend_index(2, 4, Boundary::Zero), 2);
}

}  // namespace

#include <cmath>
#include <vector>

#include "dwt/norms.h"

namespace {

// Norms against sums of squares of the published synthesis filters, computed here by hand:
// 5/3 low [1/2 1 1/2], high [-1/8 -1/4 3/4 -1/4 -1/8]; 9/7 low (-1)^n g(n), high (-1)^n h(n).
TEST(SynthesisNorms, LevelOneMatchesTheFilters) {
  const auto& k53 = dwt::get_kernel(dwt::KernelId::Float53);
  EXPECT_NEAR(dwt::synthesis_norm_1d(k53, 1, false), std::sqrt(1.5), 1e-12);
  EXPECT_NEAR(dwt::synthesis_norm_1d(k53, 1, true), std::sqrt(2 * 0.015625 + 2 * 0.0625 + 0.5625), 1e-12);
  const double g[] = {1.115087052457000, -0.591271763114250, -0.057543526228500, 0.091271763114250};
  const double h[] = {0.602949018236358, 0.266864118442875, -0.078223266528990, -0.016864118442875, 0.026748757410810};
  double low = g[0] * g[0], high = h[0] * h[0];
  for (int i = 1; i < 4; ++i) low += 2 * g[i] * g[i];
  for (int i = 1; i < 5; ++i) high += 2 * h[i] * h[i];
  const auto& k97 = dwt::get_kernel(dwt::KernelId::Irreversible97);
  EXPECT_NEAR(dwt::synthesis_norm_1d(k97, 1, false), std::sqrt(low), 1e-9);
  EXPECT_NEAR(dwt::synthesis_norm_1d(k97, 1, true), std::sqrt(high), 1e-9);
}

// Deeper levels: the level-d basis is the synthesis filter convolved with the upsampled level-(d-1)
// low-pass basis (noble identities), built here by explicit convolution of the literal taps.
std::vector<double> convolve(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
  return out;
}
std::vector<double> upsample(const std::vector<double>& a) {
  std::vector<double> out(2 * a.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) out[2 * i] = a[i];
  return out;
}
double norm(const std::vector<double>& v) {
  double e = 0;
  for (double x : v) e += x * x;
  return std::sqrt(e);
}

TEST(SynthesisNorms, DeeperLevelsMatchExplicitConvolution) {
  const std::vector<double> lo = {-0.091271763114250, -0.057543526228500, 0.591271763114250, 1.115087052457000,
                                  0.591271763114250,  -0.057543526228500, -0.091271763114250};
  const std::vector<double> hi = {0.026748757410810,  0.016864118442875, -0.078223266528990,
                                  -0.266864118442875, 0.602949018236358, -0.266864118442875,
                                  -0.078223266528990, 0.016864118442875, 0.026748757410810};
  const auto& k97 = dwt::get_kernel(dwt::KernelId::Irreversible97);
  std::vector<double> low_basis = lo, high_basis = hi;
  for (int d = 2; d <= 5; ++d) {
    high_basis = convolve(lo, upsample(high_basis));
    low_basis = convolve(lo, upsample(low_basis));
    EXPECT_NEAR(dwt::synthesis_norm_1d(k97, d, false), norm(low_basis), 1e-9) << d;
    EXPECT_NEAR(dwt::synthesis_norm_1d(k97, d, true), norm(high_basis), 1e-9) << d;
  }
  EXPECT_NEAR(dwt::synthesis_norm(k97, 3, dwt::Orientation::HL),
              dwt::synthesis_norm_1d(k97, 3, true) * dwt::synthesis_norm_1d(k97, 3, false), 1e-12);
}

}  // namespace
