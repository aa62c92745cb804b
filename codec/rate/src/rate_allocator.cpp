#include "codec/rate/rate_allocator.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace codec::rate {

namespace {

void validate_hull(std::span<const HullPoint> hull, std::size_t block) {
  int passes = 0;
  std::size_t bytes = 0;
  double slope = 0.0;
  for (std::size_t j = 0; j < hull.size(); ++j) {
    const HullPoint& p = hull[j];
    // The allocator's correctness rests on these: strictly decreasing slopes keep every
    // slope-ordered prefix in each block's own order, and growing bytes keep the sums meaningful.
    const bool slope_ok = p.slope > 0.0 && (j == 0 || p.slope < slope);
    if (p.passes <= passes || p.bytes < bytes || !slope_ok || !std::isfinite(p.distortion))
      throw std::invalid_argument("block " + std::to_string(block) + ": hull point " + std::to_string(j) +
                                  " does not continue a convex hull");
    passes = p.passes;
    bytes = p.bytes;
    slope = p.slope;
  }
}

// Every hull step's index among all blocks' steps laid end to end, by decreasing slope; equal
// slopes by that index, which grows with (block, step). A total order, so that every query (and
// every test that recomputes the order) sees the same sequence.
//
// A stable least-significant-digit radix sort on the slopes' bits: a positive double's bits (an
// infinite slope's too; the hulls are validated first, so there is no NaN or slope <= 0) order as
// the number does, so their complement orders by decreasing slope, and stability keeps equal
// slopes by index. It replaced std::sort, which took 1 ms for the 2048x2048 mosaic's ~25,000
// steps and 6 ms for the 4096x4096 one's, twice per HT encode, on one thread while the others
// waited (NVIDIA H200 machine, 16 threads).
std::vector<std::uint32_t> sorted_steps(std::span<const std::vector<HullPoint>> hulls, std::size_t step_count) {
  struct Keyed {
    std::uint64_t key;  // the slope's bits, complemented
    std::uint32_t step;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(step_count);
  for (const std::vector<HullPoint>& hull : hulls)
    for (const HullPoint& p : hull)
      keyed.push_back(Keyed{~std::bit_cast<std::uint64_t>(p.slope), static_cast<std::uint32_t>(keyed.size())});
  // 11-bit digits: six passes over 64 bits, each skipped where every key has the same digit (the
  // exponent's digits, mostly). Every digit's histogram is counted in one pass first.
  constexpr int kDigitBits = 11;
  constexpr int kDigits = (64 + kDigitBits - 1) / kDigitBits;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  auto digit = [](std::uint64_t key, int d) {
    return static_cast<std::size_t>(key >> (d * kDigitBits)) & (kBuckets - 1);
  };
  std::vector<std::uint32_t> counts(kDigits * kBuckets, 0);
  for (const Keyed& k : keyed)
    for (int d = 0; d < kDigits; ++d) ++counts[static_cast<std::size_t>(d) * kBuckets + digit(k.key, d)];
  std::vector<Keyed> scratch(keyed.size());
  for (int d = 0; d < kDigits; ++d) {
    std::uint32_t* count = counts.data() + static_cast<std::size_t>(d) * kBuckets;
    if (!keyed.empty() && count[digit(keyed[0].key, d)] == keyed.size()) continue;  // one bucket: nothing moves
    std::uint32_t offset = 0;
    for (std::size_t b = 0; b < kBuckets; ++b) offset += std::exchange(count[b], offset);
    for (const Keyed& k : keyed) scratch[count[digit(k.key, d)]++] = k;
    keyed.swap(scratch);
  }
  std::vector<std::uint32_t> order;
  order.reserve(keyed.size());
  for (const Keyed& k : keyed) order.push_back(k.step);
  return order;
}

double step_distortion(std::span<const HullPoint> hull, std::size_t point) {
  return hull[point].distortion - (point == 0 ? 0.0 : hull[point - 1].distortion);
}

std::size_t step_bytes(std::span<const HullPoint> hull, std::size_t point) {
  return hull[point].bytes - (point == 0 ? 0 : hull[point - 1].bytes);
}

}  // namespace

RateAllocator::RateAllocator(std::span<const std::vector<HullPoint>> hulls) : hulls_(hulls) {
  index_blocks();
  order_steps();
  accumulate();
}

void RateAllocator::index_blocks() {
  constexpr std::size_t index_limit = std::numeric_limits<std::uint32_t>::max();
  if (hulls_.size() > index_limit) throw std::invalid_argument("too many code-blocks for the rate allocator");
  first_step_.reserve(hulls_.size() + 1);
  first_step_.push_back(0);
  for (std::size_t b = 0; b < hulls_.size(); ++b) {
    validate_hull(hulls_[b], b);
    first_step_.push_back(first_step_.back() + hulls_[b].size());
  }
  if (first_step_.back() > index_limit) throw std::invalid_argument("too many hull steps for the rate allocator");
}

void RateAllocator::order_steps() {
  const std::vector<std::uint32_t> sorted = sorted_steps(hulls_, first_step_.back());
  // The block and hull point of each step of the end-to-end layout the keys index.
  std::vector<Step> flat;
  flat.reserve(sorted.size());
  for (std::size_t b = 0; b < hulls_.size(); ++b)
    for (std::size_t j = 0; j < hulls_[b].size(); ++j)
      flat.push_back(Step{static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(j), step_bytes(hulls_[b], j)});
  order_.reserve(sorted.size());
  rank_.assign(sorted.size(), 0);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    order_.push_back(flat[sorted[i]]);
    rank_[sorted[i]] = static_cast<std::uint32_t>(i);
  }
}

void RateAllocator::accumulate() {
  const std::size_t n = order_.size();
  prefix_bytes_.assign(n + 1, 0);
  prefix_distortion_.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Step& s = order_[i];
    prefix_bytes_[i + 1] = prefix_bytes_[i] + s.bytes;
    prefix_distortion_[i + 1] = prefix_distortion_[i] + step_distortion(hulls_[s.block], s.point);
  }
  // Lets the greedy completion stop as soon as no later step could fit, instead of walking the
  // whole tail of the order for every budget.
  suffix_min_bytes_.assign(n + 1, std::numeric_limits<std::size_t>::max());
  for (std::size_t i = n; i-- > 0;) suffix_min_bytes_[i] = std::min(suffix_min_bytes_[i + 1], order_[i].bytes);
}

std::vector<std::size_t> RateAllocator::points_in_prefix(std::size_t prefix) const {
  std::vector<std::size_t> points(hulls_.size());
  for (std::size_t b = 0; b < hulls_.size(); ++b) {
    // A block's ranks increase along its hull, so the steps inside the prefix lead its list.
    const auto begin = rank_.begin() + static_cast<std::ptrdiff_t>(first_step_[b]);
    const auto end = rank_.begin() + static_cast<std::ptrdiff_t>(first_step_[b + 1]);
    points[b] = static_cast<std::size_t>(std::lower_bound(begin, end, prefix) - begin);
  }
  return points;
}

void RateAllocator::complete_greedily(std::vector<std::size_t>& points, std::size_t& room, std::size_t from) const {
  for (std::size_t i = from; i < order_.size(); ++i) {
    if (suffix_min_bytes_[i] > room) break;
    const Step& s = order_[i];
    // Only a block's next step keeps its truncation on the hull; a block whose next step did not
    // fit takes nothing more, and steps already included cost nothing again.
    if (points[s.block] == s.point && s.bytes <= room) {
      ++points[s.block];
      room -= s.bytes;
    }
  }
}

Selection RateAllocator::for_threshold(double threshold) const { return select(hulls_, threshold); }

Selection RateAllocator::for_budget(std::size_t budget) const {
  // Longest prefix k with prefix_bytes_[k] <= budget; prefix_bytes_[0] = 0 always fits.
  const auto past = std::upper_bound(prefix_bytes_.begin(), prefix_bytes_.end(), budget);
  const std::size_t prefix = static_cast<std::size_t>(past - prefix_bytes_.begin()) - 1;
  std::vector<std::size_t> points = points_in_prefix(prefix);
  std::size_t room = budget - prefix_bytes_[prefix];
  complete_greedily(points, room, prefix);
  return selection_from_points(hulls_, points);
}

Selection RateAllocator::for_distortion(double total_weighted_energy, double max_distortion) const {
  if (std::isnan(total_weighted_energy) || std::isnan(max_distortion))
    throw std::invalid_argument("distortion target is NaN");
  const double needed = total_weighted_energy - max_distortion;
  // Shortest prefix k whose distortion reaches `needed`; the whole order if none does.
  const auto reach = std::lower_bound(prefix_distortion_.begin(), prefix_distortion_.end(), needed);
  const std::size_t prefix = std::min(static_cast<std::size_t>(reach - prefix_distortion_.begin()), order_.size());
  return selection_from_points(hulls_, points_in_prefix(prefix));
}

std::vector<std::vector<int>> RateAllocator::layers(std::span<const std::size_t> budgets) const {
  for (std::size_t l = 1; l < budgets.size(); ++l)
    if (budgets[l] < budgets[l - 1])
      throw std::invalid_argument("layer budgets must be non-decreasing; layer " + std::to_string(l) + " has " +
                                  std::to_string(budgets[l]) + " after " + std::to_string(budgets[l - 1]));
  std::vector<std::vector<int>> result;
  result.reserve(budgets.size());
  std::vector<std::size_t> points(hulls_.size(), 0);
  std::size_t used = 0;
  for (const std::size_t budget : budgets) {
    // Starting from the previous layer (not from scratch) is what keeps the layers nested: a
    // fresh greedy completion for a larger budget may drop a small step an earlier layer took.
    std::size_t room = budget - used;
    complete_greedily(points, room, 0);
    used = budget - room;
    result.push_back(selection_from_points(hulls_, points).passes);
  }
  return result;
}

}  // namespace codec::rate
