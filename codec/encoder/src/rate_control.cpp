#include "rate_control.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "ht_rate.h"
#include "reconstruction.h"
#include "codec/rate/hull.h"
#include "codec/rate/rate_allocator.h"
#include "codec/structure/error.h"
#include "dwt_cpu/cpu_backend.h"

namespace codec {
namespace {

using Clock = std::chrono::steady_clock;
// Rounds of HT candidate extensions after the first allocation (ht_rate.h) at most.
constexpr int kHtRounds = 8;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// A selection as the allocator gives it, per layer over every block of the image in tile order
// ([layer][global block]), spread back over the tiles.
// `passes` is reused as it is (rate control's trials make one selection after another, and a
// vector per block each time was a good part of a trial's time).
void per_tile(const std::vector<CodedTile>& tiles, const std::vector<std::vector<int>>& per_layer,
              LayerPasses& passes) {
  passes.resize(tiles.size());
  std::size_t g = 0;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    passes[t].resize(tiles[t].blocks.size());
    for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b, ++g) {
      std::vector<int>& block = passes[t][b];
      block.clear();
      for (const std::vector<int>& layer : per_layer) block.push_back(layer[g]);
    }
  }
}

LayerPasses per_tile(const std::vector<CodedTile>& tiles, const std::vector<std::vector<int>>& per_layer) {
  LayerPasses passes;
  per_tile(tiles, per_layer, passes);
  return passes;
}

// PSNR targets: select by estimated distortion, then rebuild the image a decoder would see,
// measure its true error and rescale the estimate's target until the measured PSNR lands in
// [target, target + 0.25 dB]. The estimate runs about 10 % optimistic (the 9/7 is not orthogonal),
// so a couple of rounds suffice.
LayerPasses select_for_psnr(const std::vector<CodedTile>& tiles, const rate::RateAllocator& allocator,
                            const std::vector<std::vector<rate::HullPoint>>& hulls, double energy,
                            const RateControlInputs& in) {
  const EncodeParams& params = in.params;
  const std::size_t layers = params.layers.size();
  dwt_cpu::CpuBackend inverse_dwt(in.pool);
  std::vector<std::vector<int>> per_layer(layers, std::vector<int>(hulls.size(), 0));
  for (std::size_t l = 0; l < layers; ++l) {
    const double goal = in.samples * in.peak * in.peak * std::pow(10.0, -params.layers[l].value / 10.0);
    const double floor_goal = goal * std::pow(10.0, -0.025);
    double aim = goal;
    std::vector<int> best;
    double best_error = -1;
    for (int round = 0; round < 8; ++round) {
      std::vector<int> chosen = allocator.for_distortion(energy, aim).passes;
      if (l > 0)
        for (std::size_t g = 0; g < chosen.size(); ++g) chosen[g] = std::max(chosen[g], per_layer[l - 1][g]);
      per_layer[l] = chosen;
      const double error = rebuilt_squared_error(in.image, in.plan, params, tiles, per_tile(tiles, per_layer),
                                                 static_cast<int>(l), inverse_dwt, in.pool);
      // Keep the cheapest selection that meets the goal.
      if (error <= goal && (best_error < 0 || error > best_error)) best = chosen, best_error = error;
      if (error <= goal && error >= floor_goal) break;
      // Measured error scales with the aimed one; aim a touch low when over the goal.
      const double correction = goal / std::max(error, 1e-9) * (error > goal ? 0.98 : 1.0);
      aim *= std::clamp(correction, 0.5, 2.0);
    }
    if (best_error < 0) {  // never met: everything coded is the best there is
      best.assign(hulls.size(), 0);
      for (std::size_t g = 0; g < hulls.size(); ++g) best[g] = hulls[g].empty() ? 0 : hulls[g].back().passes;
    }
    per_layer[l] = best;
  }
  return per_tile(tiles, per_layer);
}

// Byte targets for the whole file, headers and packet headers included: bisect a common scale of
// the layers' data budgets until the file fits the last target, as full as it gets.
// `overhead`: the file with every packet empty, measured on the first call (an empty packet's
// header is one bit, whatever its blocks hold, so it does not change between rounds). `trial`: room
// for the trial selections, kept between rounds. `last_scale`: where given, the search's first
// trial (a round that changed few blocks since the one that chose it usually fits within the
// tolerance there at once); the call leaves the scale it chose in it.
LayerPasses select_for_bytes(const std::vector<CodedTile>& tiles, const rate::RateAllocator& allocator,
                             std::size_t block_count, const RateControlInputs& in, const FileSizer& file_size,
                             std::optional<std::size_t>& empty_file, LayerPasses& trial,
                             std::optional<double>& last_scale) {
  const EncodeParams& params = in.params;
  const auto target = static_cast<std::size_t>(params.layers.back().value);
  const std::vector<std::vector<int>> none(params.layers.size(), std::vector<int>(block_count, 0));
  if (!empty_file) empty_file = file_size(per_tile(tiles, none));
  const std::size_t overhead = *empty_file;
  if (overhead > target)
    throw EncodeError("the byte target " + std::to_string(target) + " is below the " + std::to_string(overhead) +
                      " bytes the headers alone take");
  auto plan_for = [&](double scale) {
    std::vector<std::size_t> budgets;
    for (const LayerTarget& t : params.layers)
      budgets.push_back(static_cast<std::size_t>(std::max(0.0, (t.value - static_cast<double>(overhead)) * scale)));
    return allocator.layers(budgets);
  };
  // Packet headers grow with the data, so the scale ends a little below 1. The file's size grows
  // with the scale in small steps, close to linearly, so each trial aims by interpolating between
  // the closest scales known to fit and to overflow (regula falsi, Illinois variant: a side kept
  // twice in a row has its excess halved, so the bracket closes from both ends), where halving the
  // bracket needed some 15 trials. Stop once the file is within 0.005 % of the target (or a few
  // bytes): every byte left unspent is quality given away.
  std::vector<std::vector<int>> best = none;
  std::size_t best_size = overhead;
  double best_scale = 0;
  const std::size_t close_enough = target - std::max<std::size_t>(target / 20000, 4);
  const double aim = 0.5 * (static_cast<double>(close_enough) + static_cast<double>(target));
  constexpr double kTop = 1.05;
  double lo = 0, hi = kTop;  // fits at lo, overflows at hi
  double excess_lo = static_cast<double>(overhead) - aim, excess_hi = 0;
  bool hi_known = false;
  int kept_side = 0;  // +1: lo moved last time, -1: hi moved
  const bool warm = last_scale.has_value() && *last_scale > 0 && *last_scale < kTop;
  for (int iteration = 0; iteration < 40 && best_size < close_enough; ++iteration) {
    double mid = 0.5 * (lo + hi);
    if (hi_known && excess_hi > excess_lo) {
      mid = lo + (hi - lo) * (-excess_lo) / (excess_hi - excess_lo);
      const double margin = 1e-3 * (hi - lo);
      mid = std::clamp(mid, lo + margin, hi - margin);
    } else if (warm && iteration == 0) {
      mid = *last_scale;
    } else if (warm && lo > 0) {
      // The warm start fitted short of the target: the data grows about in proportion to the
      // scale, so aim a touch past the target from there, for the bracket's other side.
      const auto data = static_cast<double>(best_size - overhead);
      mid = data > 0 ? std::min(kTop, lo * (aim - static_cast<double>(overhead)) / data * (1 + 1e-4)) : kTop;
    } else if (!hi_known) {
      mid = hi;  // first, the top of the bracket: if everything fits, that is the answer
    }
    auto candidate = plan_for(mid);
    per_tile(tiles, candidate, trial);
    const std::size_t size = file_size(trial);
    const double excess = static_cast<double>(size) - aim;
    if (size <= target) {
      if (size >= best_size) best_size = size, best = std::move(candidate), best_scale = mid;
      if (!hi_known && (!warm || mid >= kTop)) break;  // the whole budget range fits
      lo = mid, excess_lo = excess;
      if (kept_side == 1) excess_hi *= 0.5;
      kept_side = 1;
    } else {
      hi = mid, excess_hi = excess, hi_known = true;
      if (kept_side == -1) excess_lo *= 0.5;
      kept_side = -1;
    }
  }
  last_scale = best_scale;
  return per_tile(tiles, best);
}

// The lowest slope the last layer takes from any block: the hull slope of each block's last chosen
// point (hulls in tile order, as control_rate builds them). +infinity when nothing is chosen.
double lowest_slope_taken(const std::vector<CodedTile>& tiles, const LayerPasses& passes,
                          const std::vector<std::vector<rate::HullPoint>>& hulls) {
  double lowest = std::numeric_limits<double>::infinity();
  std::size_t g = 0;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b, ++g) {
      const int chosen = passes[t][b].back();
      for (const rate::HullPoint& point : hulls[g])
        if (point.passes == chosen) lowest = std::min(lowest, point.slope);
    }
  return lowest;
}

// Pass skipping's check: a block that stopped early, and that the last layer takes any pass of its
// last coded bit-plane from, may have been stopped too soon. The rest stopped at least a whole
// bit-plane past the cut. A block not coded at all (its weighted energy below the stop rule's
// slope times a byte) may have been skipped too soon when even its energy, bought with one byte,
// reaches the lowest slope the allocation takes; it is coded again under a stop rule below that
// slope (the check then applies to it as to any block that stopped). A block that stopped is coded
// again with two more bit-planes than it had (kRecodePlanes; the check applies again). In
// `final_round` both are coded in full, and a block coded in full is never starved again. (Most starved blocks need
// only the significance pass of their last, quiet plane: a plane's average slope hides its best pass. In full they cost
// some twenty planes each.)
struct StarvedBlock {
  std::size_t tile = 0, block = 0;
  t1::StopRule stop;  // min_slope 0: every pass
};

constexpr int kRecodePlanes = 2;

std::vector<StarvedBlock> starved_blocks(const std::vector<CodedTile>& tiles, const LayerPasses& passes,
                                         const std::vector<std::vector<rate::HullPoint>>& hulls, bool final_round) {
  const double lowest_slope = lowest_slope_taken(tiles, passes, hulls);
  std::vector<StarvedBlock> starved;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b) {
      const t1::EncodedBlock& eb = tiles[t].blocks[b];
      if (!eb.stopped_early) continue;
      const int coded = static_cast<int>(eb.passes.size());
      if (coded == 0) {
        if (eb.energy * tiles[t].jobs[b].weight >= lowest_slope)
          starved.push_back({t, b, final_round ? t1::StopRule{} : t1::StopRule{lowest_slope / kStopSafety, 1}});
        continue;
      }
      // The last coded bit-plane's first pass: its cleanup when only the top plane was coded.
      const int last_plane_start = coded == 1 ? 0 : coded - 3;
      if (passes[t][b].back() > last_plane_start)
        starved.push_back({t, b, final_round ? t1::StopRule{} : t1::StopRule{0, 1, coded + 3 * kRecodePlanes}});
    }
  return starved;
}

}  // namespace

LayerPasses every_pass(const std::vector<CodedTile>& tiles, int layers) {
  LayerPasses passes(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (const t1::EncodedBlock& eb : tiles[t].blocks)
      passes[t].push_back(std::vector<int>(static_cast<std::size_t>(layers), static_cast<int>(eb.passes.size())));
  return passes;
}

LayerPasses control_rate(std::vector<CodedTile>& tiles, const RateControlInputs& in, const FileSizer& file_size,
                         EncodeReport& report) {
  const auto start = Clock::now();
  double recode_ms = 0;
  LayerPasses passes;
  const bool ht = in.params.ht;
  // Every block of the image, in tile order: (tile, block).
  std::vector<std::pair<std::size_t, std::size_t>> blocks;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b) blocks.emplace_back(t, b);
  std::vector<std::size_t> first_block(tiles.size() + 1, 0);  // global index of each tile's block 0
  for (std::size_t t = 0; t < tiles.size(); ++t) first_block[t + 1] = first_block[t] + tiles[t].blocks.size();
  std::optional<std::size_t> empty_file;
  // HT: the byte target's scale in the round before, where the next round's search starts. EBCOT's
  // rounds search afresh: a pass-skipping encode whose hulls end as coding every pass gives then
  // that encode's file (J2kLossy.PassSkippingIsNoWorseThanCodingEveryPass), where a warm start
  // stops at another scale within the target's tolerance (up to 0.0006 dB lower on photographs).
  std::optional<double> last_scale;
  LayerPasses trial;  // the byte targets' trial selections, one buffer for every round
  // Each round's hulls; after the first only the blocks coded again (`changed`, global indices)
  // get new ones.
  std::vector<std::vector<rate::HullPoint>> hulls(blocks.size());
  std::vector<std::size_t> changed(blocks.size());
  for (std::size_t g = 0; g < changed.size(); ++g) changed[g] = g;
  // HT: every candidate's missing MSBs from its block's settled Mb, once; extensions set their own.
  if (ht) sync_ht_missing_msbs(tiles, in.pool);
  for (int round = 0;; ++round) {
    in.pool.parallel_for(changed.size(), [&](std::size_t k) {
      const auto [t, b] = blocks[changed[k]];
      hulls[changed[k]] = rate::convex_hull(tiles[t].blocks[b].passes, tiles[t].jobs[b].weight);
    });
    double energy = 0;
    for (const auto& [t, b] : blocks) energy += tiles[t].blocks[b].energy * tiles[t].jobs[b].weight;
    const rate::RateAllocator allocator(hulls);
    std::optional<double> cold_start;
    passes = in.params.layers[0].kind == LayerTarget::Kind::Psnr
                 ? select_for_psnr(tiles, allocator, hulls, energy, in)
                 : select_for_bytes(tiles, allocator, hulls.size(), in, file_size, empty_file, trial,
                                    ht ? last_scale : cold_start);
    if (ht) {
      // HT: blocks whose choice lies at the edge of the cleanups coded get the next planes coded.
      // An edge moves by one or two planes a round and the prediction is rarely further off than that.
      const auto extensions =
          ht_blocks_at_edges(tiles, passes, lowest_slope_taken(tiles, passes, hulls), in.params, in.pool);
      if (extensions.empty() || round == kHtRounds) break;
      report.recoded_blocks += extensions.size();
      const auto extend_start = Clock::now();
      extend_ht_candidates(tiles, extensions, in.params, in.pool);
      changed.clear();
      for (const HtExtension& e : extensions) changed.push_back(first_block[e.tile] + e.block);
      const double ms = ms_since(extend_start);
      recode_ms += ms;
      report.times.tier1 += ms;
      continue;
    }
    // Starved blocks get more planes in the first rounds and every pass in the last (see
    // starved_blocks), after which none is starved: four allocations at most.
    constexpr int kFinalRound = 2;
    const auto starved = starved_blocks(tiles, passes, hulls, round == kFinalRound);
    if (starved.empty() || round > kFinalRound) break;
    report.recoded_blocks += starved.size();
    const auto recode_start = Clock::now();
    in.pool.parallel_for(starved.size(), [&](std::size_t k) {
      CodedTile& tile = tiles[starved[k].tile];
      const std::size_t b = starved[k].block;
      t1::EncodedBlock eb =
          code_block(tile, tile.jobs[b], in.params, tile.block_magnitude_bitplanes[b], starved[k].stop);
      eb.missing_msbs = tile.blocks[b].missing_msbs;  // unchanged: the same bit-planes
      tile.blocks[b] = std::move(eb);
    });
    const double ms = ms_since(recode_start);
    recode_ms += ms;
    report.times.tier1 += ms;
    changed.clear();
    for (const StarvedBlock& s : starved) changed.push_back(first_block[s.tile] + s.block);
  }
  if (ht) settle_ht_choices(tiles, passes, in.pool);
  report.times.rate_control = ms_since(start) - recode_ms;
  return passes;
}

}  // namespace codec
