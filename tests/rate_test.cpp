// PCRD-opt (codec/rate): convex hulls of tier-1 truncation points and the selections made from
// them. The optimality tests compare against brute force over every combination of truncation
// points, and the fast allocator against a plain re-implementation of its definition (sort every
// hull step by slope, walk the order greedily), so the tests check the allocator against the
// problem rather than against itself. Random instances use integer distortion decreases and
// dyadic weights, so every distortion sum is exact in double and may be compared exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "codec/rate/hull.h"
#include "codec/rate/pcrd.h"
#include "codec/rate/rate_allocator.h"
#include "codec/rate/selection.h"
#include "codec/t1/block_encoder.h"

namespace {

using codec::rate::convex_hull;
using codec::rate::HullPoint;
using codec::rate::RateAllocator;
using codec::rate::Selection;
using codec::t1::PassInfo;
using Hulls = std::vector<std::vector<HullPoint>>;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Passes from (cumulative length, distortion decrease) pairs.
std::vector<PassInfo> passes_of(std::initializer_list<std::pair<std::size_t, double>> list) {
  std::vector<PassInfo> passes;
  for (const auto& [length, decrease] : list) passes.push_back(PassInfo{length, decrease, false});
  return passes;
}

void expect_point(const HullPoint& p, int passes, std::size_t bytes, double distortion, double slope) {
  EXPECT_EQ(p.passes, passes);
  EXPECT_EQ(p.bytes, bytes);
  EXPECT_DOUBLE_EQ(p.distortion, distortion);
  if (std::isinf(slope)) {
    EXPECT_EQ(p.slope, slope);
  } else {
    EXPECT_DOUBLE_EQ(p.slope, slope);
  }
}

// A random tier-1-like pass list: lengths grow by 0..max_step bytes (0 sometimes, as when a pass
// ends inside the bytes already counted), decreases are mostly positive integers, sometimes 0 or
// negative (a refinement can move a reconstruction away from the true value).
std::vector<PassInfo> random_passes(std::mt19937& rng, int max_passes, int max_step) {
  std::uniform_int_distribution<int> count(0, max_passes);
  std::uniform_int_distribution<int> step(0, max_step);
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_int_distribution<int> gain(1, 200);
  std::vector<PassInfo> passes(static_cast<std::size_t>(count(rng)));
  std::size_t length = 0;
  for (PassInfo& p : passes) {
    length += static_cast<std::size_t>(step(rng));
    p.length = length;
    const int k = kind(rng);
    p.distortion_decrease = k == 0 ? 0.0 : k == 1 ? -static_cast<double>(gain(rng) / 4) : gain(rng);
  }
  return passes;
}

double random_weight(std::mt19937& rng) {
  static constexpr double weights[] = {1.0, 0.5, 2.0, 0.25, 4.0};
  return weights[std::uniform_int_distribution<int>(0, 4)(rng)];
}

// Weighted cumulative distortion of every truncation point (index 0 = no pass), summed the way
// convex_hull sums it, so hull points compare exactly with it.
std::vector<double> cumulative_distortion(const std::vector<PassInfo>& passes, double weight) {
  std::vector<double> d{0.0};
  double sum = 0.0;
  for (const PassInfo& p : passes) {
    sum += p.distortion_decrease;
    d.push_back(weight * sum);
  }
  return d;
}

double step_distortion(const std::vector<HullPoint>& hull, std::size_t j) {
  return hull[j].distortion - (j == 0 ? 0.0 : hull[j - 1].distortion);
}

std::size_t step_bytes(const std::vector<HullPoint>& hull, std::size_t j) {
  return hull[j].bytes - (j == 0 ? 0 : hull[j - 1].bytes);
}

// The hull point of `hull` that ends after `passes` passes (nullptr for 0); fails the test when
// `passes` is not a hull point.
const HullPoint* point_with_passes(const std::vector<HullPoint>& hull, int passes) {
  if (passes == 0) return nullptr;
  for (const HullPoint& p : hull)
    if (p.passes == passes) return &p;
  ADD_FAILURE() << passes << " passes is not a hull point";
  return nullptr;
}

// Bytes and distortion of per-block pass counts, recomputed from the hulls.
std::pair<std::size_t, double> totals_of(const Hulls& hulls, const std::vector<int>& passes) {
  std::size_t bytes = 0;
  double distortion = 0.0;
  for (std::size_t b = 0; b < hulls.size(); ++b) {
    if (const HullPoint* p = point_with_passes(hulls[b], passes[b])) {
      bytes += p->bytes;
      distortion += p->distortion;
    }
  }
  return {bytes, distortion};
}

// Every (bytes, distortion) combination of per-block truncation points, reduced to the best
// distortion reachable within any byte budget.
class BruteForce {
 public:
  // points[b] lists block b's truncation points as (bytes, distortion), including (0, 0).
  explicit BruteForce(const std::vector<std::vector<std::pair<std::size_t, double>>>& points) {
    enumerate(points, 0, 0, 0.0);
    std::sort(combos_.begin(), combos_.end());
    for (std::size_t i = 1; i < combos_.size(); ++i)
      combos_[i].second = std::max(combos_[i].second, combos_[i - 1].second);
  }
  double best_within(std::size_t budget) const {
    const auto past = std::upper_bound(combos_.begin(), combos_.end(), std::make_pair(budget, kInf));
    return past == combos_.begin() ? -kInf : std::prev(past)->second;
  }

 private:
  void enumerate(const std::vector<std::vector<std::pair<std::size_t, double>>>& points, std::size_t block,
                 std::size_t bytes, double distortion) {
    if (block == points.size()) {
      combos_.emplace_back(bytes, distortion);
      return;
    }
    for (const auto& [b, d] : points[block]) enumerate(points, block + 1, bytes + b, distortion + d);
  }
  std::vector<std::pair<std::size_t, double>> combos_;
};

BruteForce brute_over_hulls(const Hulls& hulls) {
  std::vector<std::vector<std::pair<std::size_t, double>>> points;
  for (const auto& hull : hulls) {
    points.push_back({{0, 0.0}});
    for (const HullPoint& p : hull) points.back().emplace_back(p.bytes, p.distortion);
  }
  return BruteForce(points);
}

BruteForce brute_over_passes(const std::vector<std::vector<PassInfo>>& blocks, const std::vector<double>& weights) {
  std::vector<std::vector<std::pair<std::size_t, double>>> points;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const std::vector<double> d = cumulative_distortion(blocks[b], weights[b]);
    points.push_back({{0, 0.0}});
    for (std::size_t i = 0; i < blocks[b].size(); ++i) points.back().emplace_back(blocks[b][i].length, d[i + 1]);
  }
  return BruteForce(points);
}

// Every slope on any hull, plus thresholds above and below them all: together these give every
// distinct threshold selection.
std::vector<double> all_thresholds(const Hulls& hulls) {
  std::set<double> slopes{kInf, 0.0};
  for (const auto& hull : hulls)
    for (const HullPoint& p : hull) slopes.insert(p.slope);
  return {slopes.begin(), slopes.end()};
}

struct Instance {
  std::vector<std::vector<PassInfo>> blocks;
  std::vector<double> weights;
  Hulls hulls;
};

Instance random_instance(std::mt19937& rng, int min_blocks, int max_blocks, int max_passes, int max_step) {
  Instance in;
  const int n = std::uniform_int_distribution<int>(min_blocks, max_blocks)(rng);
  for (int b = 0; b < n; ++b) {
    in.blocks.push_back(random_passes(rng, max_passes, max_step));
    in.weights.push_back(random_weight(rng));
    in.hulls.push_back(convex_hull(in.blocks.back(), in.weights.back()));
  }
  return in;
}

// ---------------------------------------------------------------------------------------------
// Convex hull

TEST(ConvexHull, NoPassesGiveAnEmptyHull) { EXPECT_TRUE(convex_hull({}, 1.0).empty()); }

TEST(ConvexHull, SinglePass) {
  const auto hull = convex_hull(passes_of({{10, 50}}), 1.0);
  ASSERT_EQ(hull.size(), 1u);
  expect_point(hull[0], 1, 10, 50, 5.0);
}

TEST(ConvexHull, ConvexCurveKeepsEveryPass) {
  const auto hull = convex_hull(passes_of({{10, 100}, {20, 50}, {30, 20}}), 1.0);
  ASSERT_EQ(hull.size(), 3u);
  expect_point(hull[0], 1, 10, 100, 10.0);
  expect_point(hull[1], 2, 20, 150, 5.0);
  expect_point(hull[2], 3, 30, 170, 2.0);
}

TEST(ConvexHull, PassUnderTheChordIsSkipped) {
  // Pass 1 gains 1/byte, but passes 1+2 together gain 5/byte: pass 1 alone is never worth taking.
  const auto hull = convex_hull(passes_of({{10, 10}, {20, 90}, {30, 20}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 2, 20, 100, 5.0);
  expect_point(hull[1], 3, 30, 120, 2.0);
}

TEST(ConvexHull, NonConvexRunPopsSeveralPoints) {
  // Slopes 3, 2, 1 from the first three, then a pass steep enough to swallow them all.
  const auto hull = convex_hull(passes_of({{10, 30}, {20, 20}, {30, 10}, {40, 340}, {50, 10}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 4, 40, 400, 10.0);
  expect_point(hull[1], 5, 50, 410, 1.0);
}

TEST(ConvexHull, ZeroAndNegativeDistortionPassesAreSkipped) {
  const auto hull = convex_hull(passes_of({{10, 50}, {15, 0}, {18, -5}, {30, 45}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 1, 10, 50, 5.0);
  expect_point(hull[1], 4, 30, 90, 2.0);  // from (10, 50): 40 more over 20 more bytes
}

TEST(ConvexHull, TrailingPassesWithoutGainAreDropped) {
  const auto hull = convex_hull(passes_of({{10, 50}, {20, 0}, {30, -1}}), 1.0);
  ASSERT_EQ(hull.size(), 1u);
  expect_point(hull[0], 1, 10, 50, 5.0);
}

TEST(ConvexHull, EqualSlopesMergeIntoOneStep) {
  // Passes 1 and 2 both gain 3/byte: collinear, so only the farther point stays (slopes strictly
  // decrease along a hull).
  const auto hull = convex_hull(passes_of({{10, 30}, {20, 30}, {30, 10}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 2, 20, 60, 3.0);
  expect_point(hull[1], 3, 30, 70, 1.0);
}

TEST(ConvexHull, FreePassesHaveInfiniteSlope) {
  // A first pass that costs no bytes is worth taking at any threshold.
  auto hull = convex_hull(passes_of({{0, 5}, {10, 20}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 1, 0, 5, kInf);
  expect_point(hull[1], 2, 10, 25, 2.0);
  // A later pass that adds no bytes replaces the point before it.
  hull = convex_hull(passes_of({{10, 20}, {10, 10}, {20, 10}}), 1.0);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 2, 10, 30, 3.0);
  expect_point(hull[1], 3, 20, 40, 1.0);
}

TEST(ConvexHull, WeightScalesDistortionAndSlope) {
  const auto hull = convex_hull(passes_of({{10, 100}, {20, 50}}), 0.25);
  ASSERT_EQ(hull.size(), 2u);
  expect_point(hull[0], 1, 10, 25, 2.5);
  expect_point(hull[1], 2, 20, 37.5, 1.25);
  EXPECT_TRUE(convex_hull(passes_of({{10, 100}}), 0.0).empty());
}

TEST(ConvexHull, RejectsInvalidInput) {
  EXPECT_THROW(convex_hull(passes_of({{10, 1}, {9, 1}}), 1.0), std::invalid_argument);
  EXPECT_THROW(convex_hull(passes_of({{10, 1}}), -1.0), std::invalid_argument);
  EXPECT_THROW(convex_hull(passes_of({{10, 1}}), kInf), std::invalid_argument);
  EXPECT_THROW(convex_hull(passes_of({{10, std::nan("")}}), 1.0), std::invalid_argument);
}

TEST(ConvexHull, RandomPassListsGiveConsistentHulls) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto passes = random_passes(rng, 40, 30);
    const double weight = random_weight(rng);
    const auto hull = convex_hull(passes, weight);
    const std::vector<double> d = cumulative_distortion(passes, weight);
    std::size_t bytes = 0;
    double distortion = 0.0;
    int count = 0;
    for (std::size_t j = 0; j < hull.size(); ++j) {
      const HullPoint& p = hull[j];
      ASSERT_GT(p.passes, count);
      ASSERT_LE(static_cast<std::size_t>(p.passes), passes.size());
      // A hull point is a real truncation point: its bytes and distortion are the sums through it.
      EXPECT_EQ(p.bytes, passes[static_cast<std::size_t>(p.passes) - 1].length);
      EXPECT_EQ(p.distortion, d[static_cast<std::size_t>(p.passes)]);
      EXPECT_GT(p.slope, 0.0);
      if (j > 0) {
        EXPECT_LT(p.slope, hull[j - 1].slope);
      }
      if (p.bytes == bytes) {
        EXPECT_EQ(p.slope, kInf);
      } else {
        EXPECT_EQ(p.slope, (p.distortion - distortion) / static_cast<double>(p.bytes - bytes));
      }
      count = p.passes;
      bytes = p.bytes;
      distortion = p.distortion;
    }
    // Support lines: at each hull slope, no truncation point (hull or not) beats the hull.
    for (const HullPoint& h : hull) {
      if (std::isinf(h.slope)) continue;
      double best = 0.0;  // the origin
      for (const HullPoint& q : hull) best = std::max(best, q.distortion - h.slope * static_cast<double>(q.bytes));
      for (std::size_t i = 0; i < passes.size(); ++i)
        EXPECT_LE(d[i + 1] - h.slope * static_cast<double>(passes[i].length), best + 1e-9 * (1 + std::abs(best)));
    }
    // Every pass with a gain after the hull's end would have extended it.
    const double end = hull.empty() ? 0.0 : hull.back().distortion;
    for (double v : d) EXPECT_LE(v, end);
  }
}

TEST(ConvexHull, HullOfARealCodeBlock) {
  std::mt19937 rng(7);
  std::normal_distribution<double> laplace_ish(0.0, 40.0);
  std::vector<std::int32_t> c(32 * 32);
  for (auto& v : c) v = static_cast<std::int32_t>(std::clamp(laplace_ish(rng), -255.0, 255.0));
  const auto enc = codec::t1::encode_block(c, 32, 32, codec::t1::Orientation::HL, 8, {});
  ASSERT_FALSE(enc.passes.empty());
  const auto hull = convex_hull(enc.passes, 1.0);
  ASSERT_FALSE(hull.empty());
  EXPECT_LE(hull.back().bytes, enc.data.size());
  for (std::size_t j = 1; j < hull.size(); ++j) EXPECT_LT(hull[j].slope, hull[j - 1].slope);
}

// ---------------------------------------------------------------------------------------------
// Selections

TEST(Select, ThresholdTakesEachBlockThroughItsSteepEnoughPoints) {
  const Hulls hulls{convex_hull(passes_of({{10, 100}, {20, 50}, {30, 20}}), 1.0),  // slopes 10, 5, 2
                    convex_hull(passes_of({{4, 24}, {8, 12}}), 1.0),               // slopes 6, 3
                    {}};
  Selection s = codec::rate::select(hulls, 5.0);
  EXPECT_EQ(s.passes, (std::vector<int>{2, 1, 0}));
  EXPECT_EQ(s.bytes, 24u);
  EXPECT_DOUBLE_EQ(s.distortion, 174.0);
  s = codec::rate::select(hulls, 100.0);
  EXPECT_EQ(s.passes, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(s.bytes, 0u);
  s = codec::rate::select(hulls, 0.0);
  EXPECT_EQ(s.passes, (std::vector<int>{3, 2, 0}));
  EXPECT_EQ(s.bytes, 38u);
  EXPECT_THROW(codec::rate::select(hulls, std::nan("")), std::invalid_argument);
  EXPECT_EQ(RateAllocator(hulls).for_threshold(5.0).passes, (std::vector<int>{2, 1, 0}));
}

TEST(Select, BudgetSplitsTiesAndFillsLeftoverRoom) {
  // Three blocks with an equal first slope of 4: a threshold either takes all three (30 bytes) or
  // none; a budget of 20 takes two of them (ties by block order). The last block's smaller step
  // (slope 1) then fills the remaining room.
  const Hulls hulls{convex_hull(passes_of({{10, 40}}), 1.0), convex_hull(passes_of({{10, 40}}), 1.0),
                    convex_hull(passes_of({{10, 40}}), 1.0), convex_hull(passes_of({{3, 3}}), 1.0)};
  Selection s = codec::rate::select_for_budget(hulls, 25);
  EXPECT_EQ(s.passes, (std::vector<int>{1, 1, 0, 1}));
  EXPECT_EQ(s.bytes, 23u);
  EXPECT_DOUBLE_EQ(s.distortion, 83.0);
  s = codec::rate::select_for_budget(hulls, 9);
  EXPECT_EQ(s.passes, (std::vector<int>{0, 0, 0, 1}));
  s = codec::rate::select_for_budget(hulls, 1000);
  EXPECT_EQ(s.passes, (std::vector<int>{1, 1, 1, 1}));
  EXPECT_EQ(s.bytes, 33u);
}

TEST(Select, SlopesOneUlpApartKeepTheirOrder) {
  // The allocator sorts the slopes by their bits: blocks whose one step differs from the next
  // block's in the last bit of the mantissa alone (and one infinite slope, a free pass) must still
  // be taken steepest first, each budget of k steps taking exactly the k steepest.
  Hulls hulls;
  std::vector<double> slopes;
  double slope = 3.0;
  for (int b = 0; b < 12; ++b) {
    slope = std::nextafter(slope, b % 2 ? 10.0 : 0.0);  // up, down, up, ...: not in block order
    if (b % 2) slope = std::nextafter(slope, 10.0);
    slopes.push_back(slope);
    hulls.push_back({HullPoint{1, 8, slope * 8, slope}});
  }
  hulls.push_back({HullPoint{1, 0, 1.0, std::numeric_limits<double>::infinity()}});
  slopes.push_back(std::numeric_limits<double>::infinity());
  const RateAllocator allocator(hulls);
  std::vector<std::size_t> by_slope(slopes.size());
  for (std::size_t i = 0; i < by_slope.size(); ++i) by_slope[i] = i;
  std::stable_sort(by_slope.begin(), by_slope.end(),
                   [&](std::size_t a, std::size_t b) { return slopes[a] > slopes[b]; });
  for (std::size_t k = 0; k <= 12; ++k) {
    std::vector<int> expected(hulls.size(), 0);
    for (std::size_t i = 0; i < k + 1; ++i) expected[by_slope[i]] = 1;  // the free step and the k steepest
    EXPECT_EQ(allocator.for_budget(8 * k).passes, expected) << k << " steps";
  }
}

TEST(Select, GreedyCompletionOnlyTakesABlocksNextStep) {
  // Block 0: a 10-byte step (slope 10) then a 1-byte step (slope 5). Block 1: one 6-byte step
  // (slope 6). With 8 bytes, block 1's step fits but block 0's first does not, so block 0's cheap
  // second step must not be taken either (it is not a truncation point without the first).
  const Hulls hulls{convex_hull(passes_of({{10, 100}, {11, 5}}), 1.0), convex_hull(passes_of({{6, 36}}), 1.0)};
  const Selection s = codec::rate::select_for_budget(hulls, 8);
  EXPECT_EQ(s.passes, (std::vector<int>{0, 1}));
  EXPECT_EQ(s.bytes, 6u);
}

TEST(Select, EmptyInputs) {
  const Hulls none;
  EXPECT_TRUE(codec::rate::select_for_budget(none, 100).passes.empty());
  EXPECT_TRUE(codec::rate::select_for_distortion(none, 10.0, 1.0).passes.empty());
  const std::vector<std::size_t> budgets{1, 2};
  EXPECT_EQ(codec::rate::layer_passes(none, budgets).size(), 2u);
  const Hulls empty_blocks(3);
  const Selection s = codec::rate::select_for_budget(empty_blocks, 100);
  EXPECT_EQ(s.passes, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(s.bytes, 0u);
}

TEST(RateAllocatorTest, RejectsHullsThatAreNotHulls) {
  const Hulls rising{{HullPoint{1, 10, 10, 1.0}, HullPoint{2, 20, 30, 2.0}}};
  EXPECT_THROW(RateAllocator{rising}, std::invalid_argument);
  const Hulls backwards{{HullPoint{2, 10, 10, 1.0}, HullPoint{1, 20, 15, 0.5}}};
  EXPECT_THROW(RateAllocator{backwards}, std::invalid_argument);
  const Hulls nan_slope{{HullPoint{1, 10, 10, std::nan("")}}};
  EXPECT_THROW(RateAllocator{nan_slope}, std::invalid_argument);
}

// For budgets equal to a threshold selection's bytes, the budget answer is that selection and
// matches brute force over hull points, and over every pass truncation too (the Lagrangian
// argument: no truncation point beats the hull at its own rate). For any budget it fits, its bytes
// grow with the budget, it is at least as good as the best threshold selection that fits, and it
// trails the optimum by at most one hull step's distortion - at most one step per block, which is
// the bound asked for, and in fact one step overall.
TEST(Select, BudgetMatchesBruteForce) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE(trial);
    const Instance in = random_instance(rng, 3, 5, 6, 12);
    const RateAllocator alloc(in.hulls);
    const BruteForce over_hulls = brute_over_hulls(in.hulls);
    const BruteForce over_passes = brute_over_passes(in.blocks, in.weights);

    const std::vector<double> thresholds = all_thresholds(in.hulls);
    std::vector<Selection> by_threshold;
    for (double t : thresholds) by_threshold.push_back(codec::rate::select(in.hulls, t));
    for (const Selection& t : by_threshold) {
      const Selection s = alloc.for_budget(t.bytes);
      EXPECT_EQ(s.bytes, t.bytes);
      EXPECT_EQ(s.distortion, t.distortion);
      EXPECT_EQ(s.distortion, over_hulls.best_within(t.bytes));
      EXPECT_GE(s.distortion, over_passes.best_within(t.bytes));
    }

    double biggest_step = 0.0;
    for (const auto& hull : in.hulls)
      for (std::size_t j = 0; j < hull.size(); ++j) biggest_step = std::max(biggest_step, step_distortion(hull, j));
    std::size_t previous_bytes = 0;
    for (std::size_t budget = 0; budget <= alloc.total_bytes() + 3; ++budget) {
      const Selection s = alloc.for_budget(budget);
      ASSERT_EQ(s.passes.size(), in.hulls.size());
      const auto [bytes, distortion] = totals_of(in.hulls, s.passes);
      EXPECT_EQ(s.bytes, bytes);
      EXPECT_EQ(s.distortion, distortion);
      EXPECT_LE(s.bytes, budget);
      EXPECT_GE(s.bytes, previous_bytes);
      previous_bytes = s.bytes;
      for (const Selection& t : by_threshold) {
        if (t.bytes <= budget) {
          EXPECT_GE(s.distortion, t.distortion);
        }
      }
      EXPECT_LE(over_hulls.best_within(budget) - s.distortion, biggest_step);
    }
    EXPECT_EQ(alloc.for_budget(alloc.total_bytes()).distortion, alloc.total_distortion());
    EXPECT_EQ(codec::rate::select_for_budget(in.hulls, alloc.total_bytes() / 2).passes,
              alloc.for_budget(alloc.total_bytes() / 2).passes);
  }
}

TEST(Select, DistortionTargetIsMetWithFewestBytes) {
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const Instance in = random_instance(rng, 1, 8, 10, 20);
    const RateAllocator alloc(in.hulls);
    // Energy beyond what all passes remove: the residual of a lossy code-block.
    const double energy = alloc.total_distortion() + 1000.0;
    std::vector<Selection> by_threshold;
    for (double t : all_thresholds(in.hulls)) by_threshold.push_back(codec::rate::select(in.hulls, t));

    std::vector<double> targets{energy, energy + 5.0, 1000.0, 999.0, 0.0};
    for (const Selection& t : by_threshold) {
      targets.push_back(energy - t.distortion);
      targets.push_back(energy - t.distortion + 0.5);
      targets.push_back(energy - t.distortion - 0.5);
    }
    for (double max_distortion : targets) {
      const Selection s = codec::rate::select_for_distortion(in.hulls, energy, max_distortion);
      EXPECT_EQ(s.passes, alloc.for_distortion(energy, max_distortion).passes);
      const auto [bytes, distortion] = totals_of(in.hulls, s.passes);
      EXPECT_EQ(s.bytes, bytes);
      if (energy - alloc.total_distortion() > max_distortion) {
        // Unreachable: everything is the best there is.
        EXPECT_EQ(s.bytes, alloc.total_bytes());
        continue;
      }
      EXPECT_LE(energy - s.distortion, max_distortion);
      for (const Selection& t : by_threshold) {
        if (energy - t.distortion <= max_distortion) {
          EXPECT_LE(s.bytes, t.bytes);
        }
      }
      if (max_distortion >= energy) {
        EXPECT_EQ(s.bytes, 0u);
      }
    }
  }
  EXPECT_THROW(codec::rate::select_for_distortion(Hulls{}, std::nan(""), 1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Quality layers

void check_layers(const Hulls& hulls, const std::vector<std::size_t>& budgets,
                  const std::vector<std::vector<int>>& layers) {
  ASSERT_EQ(layers.size(), budgets.size());
  for (std::size_t l = 0; l < layers.size(); ++l) {
    SCOPED_TRACE(l);
    ASSERT_EQ(layers[l].size(), hulls.size());
    EXPECT_LE(totals_of(hulls, layers[l]).first, budgets[l]);
    if (l == 0) continue;
    for (std::size_t b = 0; b < hulls.size(); ++b) EXPECT_GE(layers[l][b], layers[l - 1][b]);
  }
}

TEST(Layers, NestedAndWithinEachBudget) {
  std::mt19937 rng(555);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const Instance in = random_instance(rng, 1, 60, 15, 25);
    const RateAllocator alloc(in.hulls);
    std::uniform_int_distribution<std::size_t> pick(0, alloc.total_bytes() + 10);
    std::vector<std::size_t> budgets(std::uniform_int_distribution<std::size_t>(1, 8)(rng));
    for (auto& b : budgets) b = pick(rng);
    std::sort(budgets.begin(), budgets.end());
    if (trial % 3 == 0) budgets.push_back(budgets.back());  // a repeated budget adds nothing
    const auto layers = codec::rate::layer_passes(in.hulls, budgets);
    check_layers(in.hulls, budgets, layers);
    EXPECT_EQ(layers.front(), alloc.for_budget(budgets.front()).passes);
    if (trial % 3 == 0) {
      EXPECT_EQ(layers.back(), layers[layers.size() - 2]);
    }
    if (budgets.back() >= alloc.total_bytes()) {
      EXPECT_EQ(totals_of(in.hulls, layers.back()).first, alloc.total_bytes());
    }
  }
}

TEST(Layers, LaterLayersKeepSmallStepsEarlierLayersTook) {
  // Budget 8: block 0's 10-byte step does not fit, block 1's 6-byte step does. Budget 12: a fresh
  // selection would take block 0's step (slope 10) and have no room for block 1's; the layer must
  // keep block 1's step instead of dropping it.
  const Hulls hulls{convex_hull(passes_of({{10, 100}}), 1.0), convex_hull(passes_of({{6, 36}}), 1.0)};
  EXPECT_EQ(codec::rate::select_for_budget(hulls, 12).passes, (std::vector<int>{1, 0}));
  const std::vector<std::size_t> budgets{8, 12, 16};
  const auto layers = codec::rate::layer_passes(hulls, budgets);
  check_layers(hulls, budgets, layers);
  EXPECT_EQ(layers[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(layers[1], (std::vector<int>{0, 1}));
  EXPECT_EQ(layers[2], (std::vector<int>{1, 1}));
}

TEST(Layers, RejectsDecreasingBudgets) {
  const Hulls hulls{convex_hull(passes_of({{10, 100}}), 1.0)};
  const std::vector<std::size_t> budgets{10, 5};
  EXPECT_THROW(codec::rate::layer_passes(hulls, budgets), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Scale

// A code-block of a real image, roughly: each bit-plane costs more bytes and buys less distortion
// than the one above it, with noise enough to make the curve non-convex in places.
std::vector<PassInfo> image_like_passes(std::mt19937& rng) {
  const int planes = std::uniform_int_distribution<int>(0, 11)(rng);
  std::uniform_real_distribution<double> noise(0.3, 1.7);
  std::vector<PassInfo> passes;
  std::size_t length = 0;
  double energy = std::ldexp(1.0, 2 * planes + 4);
  for (int pass = 0; pass < (planes > 0 ? 3 * planes - 2 : 0); ++pass) {
    if (pass % 3 == 0) energy /= 4;
    length += static_cast<std::size_t>(noise(rng) * (2 + pass * 4));
    passes.push_back(PassInfo{length, std::round(energy * noise(rng)), pass % 3 == 0});
  }
  return passes;
}

// The allocator's definition, written plainly: every step in slope order (ties by block, then
// step), taken whenever it is its block's next step and still fits.
class NaiveGreedy {
 public:
  explicit NaiveGreedy(const Hulls& hulls) : hulls_(hulls) {
    for (std::size_t b = 0; b < hulls.size(); ++b)
      for (std::size_t j = 0; j < hulls[b].size(); ++j) steps_.push_back({b, j});
    std::sort(steps_.begin(), steps_.end(), [&](const auto& x, const auto& y) {
      const double sx = hulls[x.first][x.second].slope, sy = hulls[y.first][y.second].slope;
      return sx != sy ? sx > sy : x < y;
    });
  }
  std::vector<int> for_budget(std::size_t budget) const {
    std::vector<std::size_t> taken(hulls_.size(), 0);
    for (const auto& [b, j] : steps_) {
      const std::size_t cost = step_bytes(hulls_[b], j);
      if (taken[b] == j && cost <= budget) {
        taken[b] = j + 1;
        budget -= cost;
      }
    }
    std::vector<int> passes(hulls_.size(), 0);
    for (std::size_t b = 0; b < hulls_.size(); ++b)
      if (taken[b] > 0) passes[b] = hulls_[b][taken[b] - 1].passes;
    return passes;
  }

 private:
  const Hulls& hulls_;
  std::vector<std::pair<std::size_t, std::size_t>> steps_;
};

TEST(Scale, HundredThousandBlocksTwentyBudgets) {
  std::mt19937 rng(31337);
  Hulls hulls;
  hulls.reserve(100000);
  for (int b = 0; b < 100000; ++b) hulls.push_back(convex_hull(image_like_passes(rng), random_weight(rng)));
  const RateAllocator alloc(hulls);
  const NaiveGreedy naive(hulls);
  ASSERT_GT(alloc.total_bytes(), 0u);
  std::size_t biggest_step = 0;
  for (const auto& hull : hulls)
    for (std::size_t j = 0; j < hull.size(); ++j) biggest_step = std::max(biggest_step, step_bytes(hull, j));

  std::vector<std::size_t> budgets;
  for (int i = 1; i <= 20; ++i) budgets.push_back(alloc.total_bytes() / 21 * static_cast<std::size_t>(i) + 7);
  std::size_t previous = 0;
  for (std::size_t budget : budgets) {
    SCOPED_TRACE(budget);
    const Selection s = alloc.for_budget(budget);
    EXPECT_LE(s.bytes, budget);
    EXPECT_GE(s.bytes, previous);
    previous = s.bytes;
    EXPECT_EQ(s.passes, naive.for_budget(budget));
    // Greedy completion leaves less room unused than the biggest hull step: any step it passed
    // over was bigger than the room left at that moment.
    EXPECT_LT(budget - s.bytes, biggest_step);
  }
  check_layers(hulls, budgets, alloc.layers(budgets));
  const Selection at_threshold = alloc.for_threshold(hulls[0].empty() ? 1.0 : hulls[0].back().slope);
  EXPECT_EQ(alloc.for_budget(at_threshold.bytes).distortion, at_threshold.distortion);
}

}  // namespace
