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
