#include "codec/encoder/encoder.h"

#include <algorithm>

#include "codec/codestream/codestream_writer.h"
#include "codec/codestream/jp2.h"
#include "codec/codestream/main_header.h"
#include "codec/encoder/reconstruction.h"
#include "codec/encoder/tile_coder.h"
#include "codec/structure/error.h"
#include "codec/tier2/packet_writer.h"
#include "codec/tier2/progression.h"
#include "codec/rate/pcrd.h"
#include "codec/rate/rate_allocator.h"
#include "dwt_cpu/cpu_backend.h"
#include "codec/encoder/dwt_choice.h"

#include <chrono>
#include <cmath>
#include <memory>

namespace codec {
namespace {

cs::MainHeader main_header(const SourceImage& image, const EncodeParams& params, const CodingPlan& plan,
                           const std::vector<int>& guard_bits, int layers) {
  cs::MainHeader h;
  const ImageGrid& g = plan.grid;
  h.siz.xsiz = static_cast<std::uint64_t>(g.image.x1);
  h.siz.ysiz = static_cast<std::uint64_t>(g.image.y1);
  h.siz.xosiz = static_cast<std::uint64_t>(g.image.x0);
  h.siz.yosiz = static_cast<std::uint64_t>(g.image.y0);
  h.siz.xtsiz = static_cast<std::uint64_t>(g.tile_width);
  h.siz.ytsiz = static_cast<std::uint64_t>(g.tile_height);
  h.siz.xtosiz = static_cast<std::uint64_t>(g.tile_x0);
  h.siz.ytosiz = static_cast<std::uint64_t>(g.tile_y0);
  for (const SourceComponent& c : image.components)
    h.siz.components.push_back(cs::SizComponent{static_cast<unsigned>(c.precision), c.is_signed, 1, 1});

  h.cod.sop = params.sop;
  h.cod.eph = params.eph;
  h.cod.order = static_cast<cs::ProgressionOrder>(static_cast<int>(params.order));
  h.cod.layers = static_cast<unsigned>(layers);
  h.cod.mct = plan.rct || plan.ict;
  const CodingStyle& style = plan.styles[0];
  h.cod.style.levels = static_cast<unsigned>(style.levels);
  h.cod.style.xcb = static_cast<unsigned>(style.xcb);
  h.cod.style.ycb = static_cast<unsigned>(style.ycb);
  h.cod.style.block_style = params.block_style.to_spcod();
  h.cod.style.transform = params.lossless ? cs::WaveletTransform::Reversible5x3 : cs::WaveletTransform::Irreversible9x7;
  if (style.explicit_precincts())
    for (int r = 0; r <= style.levels; ++r) {
      const auto [ppx, ppy] = style.precinct(r);
      h.cod.style.precincts.push_back(cs::PrecinctSize{static_cast<unsigned>(ppx), static_cast<unsigned>(ppy)});
    }

  auto quantization = [&](std::size_t c) {
    cs::Quantization q;
    q.guard_bits = static_cast<unsigned>(guard_bits[c]);
    const ComponentQuantization& cq = plan.quantization[c];
    q.style = params.lossless ? cs::QuantizationStyle::None : cs::QuantizationStyle::ScalarExpounded;
    for (std::size_t b = 0; b < cq.exponents.size(); ++b)
      q.steps.push_back(cs::StepSize{static_cast<unsigned>(cq.exponents[b]),
                                     params.lossless ? 0u : static_cast<unsigned>(cq.mantissas[b])});
    return q;
  };
  h.qcd = quantization(0);
  for (std::size_t c = 1; c < image.components.size(); ++c) {
    cs::Quantization q = quantization(c);
    if (q.guard_bits != h.qcd.guard_bits || q.steps.size() != h.qcd.steps.size() ||
        !std::equal(q.steps.begin(), q.steps.end(), h.qcd.steps.begin(),
                    [](const cs::StepSize& a, const cs::StepSize& b) { return a.exponent == b.exponent && a.mantissa == b.mantissa; }))
      h.qccs.push_back(cs::Qcc{static_cast<unsigned>(c), q});
  }
  if (!params.comment.empty()) h.comments.push_back(cs::latin_comment(params.comment));
  return h;
}

t2::Order to_t2(Progression p) { return static_cast<t2::Order>(static_cast<int>(p)); }

// Express missing bit-planes against the guard bits the header states.
void apply_guard_bits(CodedTile& coded, const std::vector<int>& plan_guard, const std::vector<int>& final_guard) {
  for (const TileComponent& tc : coded.tile.components)
    for (const Resolution& res : tc.resolutions)
      for (const Precinct& p : res.precincts)
        for (const PrecinctBand& pb : p.bands)
          for (const CodeBlock& cb : pb.blocks)
            coded.blocks[cb.index].missing_msbs += final_guard[static_cast<std::size_t>(tc.component)] -
                                                   plan_guard[static_cast<std::size_t>(tc.component)];
}

// Tier-2: every packet of the tile in progression order. `passes[b]` lists block b's cumulative
// passes after each layer.
std::vector<std::uint8_t> tile_body(const CodedTile& coded, const EncodeParams& params,
                                    const std::vector<std::vector<int>>& passes, int layers) {
  const Tile& tile = coded.tile;

  std::vector<t2::ComponentGeometry> geometry;
  // One packet writer per precinct, in (component, resolution, precinct) order.
  std::vector<std::vector<std::vector<t2::PrecinctPacketWriter>>> writers(tile.components.size());
  for (const TileComponent& tc : tile.components) {
    t2::ComponentGeometry cg;
    auto& by_resolution = writers[static_cast<std::size_t>(tc.component)];
    for (const Resolution& res : tc.resolutions) {
      cg.resolutions.push_back(t2::ResolutionGeometry{res.rect.x0, res.rect.y0, res.rect.x1, res.rect.y1, res.ppx, res.ppy,
                                                      res.precincts_wide, res.precincts_high});
      auto& list = by_resolution.emplace_back();
      for (const Precinct& p : res.precincts) {
        std::vector<t2::PrecinctBand> bands;
        for (const PrecinctBand& pb : p.bands) {
          t2::PrecinctBand band;
          band.cols = pb.cols;
          band.rows = pb.rows;
          for (const CodeBlock& cb : pb.blocks) {
            const t1::EncodedBlock& eb = coded.blocks[cb.index];
            band.blocks.push_back(t2::CodeBlockCoding{&eb, passes[cb.index]});
          }
          bands.push_back(std::move(band));
        }
        list.emplace_back(std::move(bands), params.block_style);
      }
    }
    geometry.push_back(std::move(cg));
  }
  std::vector<std::uint8_t> body;
  std::uint16_t sequence = 0;
  for (const t2::PacketId& id :
       t2::progression(to_t2(params.order), layers, tile.rect.x0, tile.rect.y0, tile.rect.x1, tile.rect.y1, geometry))
    writers[static_cast<std::size_t>(id.component)][static_cast<std::size_t>(id.resolution)][static_cast<std::size_t>(id.precinct)]
        .write_packet(id.layer, params.sop, params.eph, sequence++, body);
  return body;
}

std::vector<std::uint8_t> encode_image(const SourceImage& image, SourceImage* consumable, const EncodeParams& params,
                                       FileFormat format, EncodeReport* report_out) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
  EncodeReport report;
  const auto setup_start = Clock::now();
  const CodingPlan plan = make_plan(image, params);
  // One set of worker threads for every stage: the DWT, the component transform, tier-1.
  dwt_cpu::ThreadPool pool(params.threads);
  report.threads = pool.size();
  double samples = 0;
  for (const SourceComponent& c : image.components) samples += static_cast<double>(c.samples.size());
  DwtChoice dwt = choose_dwt(params, samples, pool);
  report.dwt_backend = dwt.name;
  report.dwt_reason = dwt.reason;
  report.times.gl_context = dwt.gl_context_ms;
  report.times.shader_compile = dwt.shader_compile_ms;
  dwt_cpu::CpuBackend reversible_dwt(pool);

  std::vector<CodedTile> tiles;
  const int count = plan.grid.tile_count();
  tiles.reserve(static_cast<std::size_t>(count));
  std::vector<int> plan_guard, final_guard;
  for (const auto& q : plan.quantization) plan_guard.push_back(q.guard_bits);
  final_guard = plan_guard;
  const std::size_t all_blocks = params.progress ? count_code_blocks(plan) : 0;
  report.times.setup = since(setup_start) - report.times.gl_context - report.times.shader_compile;
  std::size_t blocks_before = 0;
  // Pass skipping needs a target to predict from: each tile gets its share of the last layer's
  // bytes (less a little for the headers), or of the squared error its PSNR allows (less a fifth:
  // the rate-distortion estimate runs optimistic, so the PSNR loop aims below the goal). The
  // prediction only sets where blocks stop, with a wide margin.
  const bool skipping = params.skip_passes && !params.lossless && !params.layers.empty();
  int peak_bits = 0;
  for (const SourceComponent& c : image.components) peak_bits = std::max(peak_bits, c.precision);
  const double peak = std::ldexp(1.0, peak_bits) - 1;
  auto tile_target = [&](const Tile& tile) {
    Tier1Target target;
    if (!skipping) return target;
    double tile_samples = 0;
    for (const TileComponent& tc : tile.components) tile_samples += static_cast<double>(tc.rect.width() * tc.rect.height());
    const double share = tile_samples / std::max(1.0, samples);
    const LayerTarget& last = params.layers.back();
    if (last.kind == LayerTarget::Kind::Bytes) {
      target = {Tier1Target::Kind::Bytes, 0.97 * last.value * share};
    } else {
      const double goal = samples * peak * peak * std::pow(10.0, -last.value / 10.0);
      target = {Tier1Target::Kind::Distortion, 0.8 * goal * share};
    }
    return target;
  };
  for (int t = 0; t < count; ++t) {
    const Tier1Target target = tile_target(build_tile(plan.grid, plan.sampling, plan.styles, t));
    tiles.push_back(code_tile(image, consumable, plan, params, t, *dwt.backend, reversible_dwt, pool, report.times, target,
                              blocks_before, all_blocks));
    blocks_before += tiles.back().blocks.size();
    for (std::size_t c = 0; c < final_guard.size(); ++c)
      final_guard[c] = std::max(final_guard[c], tiles.back().guard_bits_needed[c]);
  }
  for (CodedTile& tile : tiles) apply_guard_bits(tile, plan_guard, final_guard);

  const int layers = params.layers.empty() ? 1 : static_cast<int>(params.layers.size());
  // Cumulative passes per layer for every block of every tile; by default everything in layer 0.
  std::vector<std::vector<std::vector<int>>> passes(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (const auto& eb : tiles[t].blocks) passes[t].push_back(std::vector<int>(static_cast<std::size_t>(layers), static_cast<int>(eb.passes.size())));

  const cs::MainHeader header = main_header(image, params, plan, final_guard, layers);
  auto assemble = [&]() {
    cs::CodestreamWriter writer(header);
    for (std::size_t t = 0; t < tiles.size(); ++t)
      writer.add_tile_part(static_cast<unsigned>(tiles[t].tile.index), 0, 1, tile_body(tiles[t], params, passes[t], layers));
    std::vector<std::uint8_t> codestream = writer.finish();
    if (format == FileFormat::Jp2) return cs::wrap_jp2(codestream, cs::jp2_header_for(header.siz));
    return codestream;
  };

  const auto rate_start = Clock::now();
  double recode_ms = 0;
  // Rate control; with pass skipping, again after recoding blocks the first allocation found
  // stopped too soon (at most twice: the recoded blocks have every pass).
  for (int recode_round = 0; !params.layers.empty(); ++recode_round) {
    // Rate control over every block of the image: one slope threshold per layer (PCRD-opt).
    std::vector<std::vector<rate::HullPoint>> hulls;
    double energy = 0;
    for (const CodedTile& tile : tiles)
      for (std::size_t b = 0; b < tile.blocks.size(); ++b) {
        hulls.push_back(rate::convex_hull(tile.blocks[b].passes, tile.jobs[b].weight));
        energy += tile.blocks[b].energy * tile.jobs[b].weight;
      }
    const rate::RateAllocator allocator(hulls);
    auto apply = [&](const std::vector<std::vector<int>>& per_layer) {  // [layer][global block]
      std::size_t g = 0;
      for (std::size_t t = 0; t < tiles.size(); ++t)
        for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b, ++g)
          for (int l = 0; l < layers; ++l) {
            passes[t][b][static_cast<std::size_t>(l)] = per_layer[static_cast<std::size_t>(l)][g];
          }
    };
    if (params.layers[0].kind == LayerTarget::Kind::Psnr) {
      // Select by estimated distortion, then rebuild the image a decoder would see, measure its
      // true error and rescale the estimate's target until the measured PSNR lands in
      // [target, target + 0.25 dB]. The estimate runs about 10 % optimistic (the 9/7 is not
      // orthogonal), so a couple of rounds suffice.
      dwt_cpu::CpuBackend inverse_dwt(pool);
      std::vector<std::vector<int>> per_layer(static_cast<std::size_t>(layers), std::vector<int>(hulls.size(), 0));
      for (int l = 0; l < layers; ++l) {
        const double goal = samples * peak * peak * std::pow(10.0, -params.layers[static_cast<std::size_t>(l)].value / 10.0);
        const double floor_goal = goal * std::pow(10.0, -0.025);
        double aim = goal;
        std::vector<int> best;
        double best_error = -1;
        for (int round = 0; round < 8; ++round) {
          rate::Selection selection = allocator.for_distortion(energy, aim);
          std::vector<int> chosen = selection.passes;
          if (l > 0)
            for (std::size_t g = 0; g < chosen.size(); ++g) chosen[g] = std::max(chosen[g], per_layer[static_cast<std::size_t>(l - 1)][g]);
          per_layer[static_cast<std::size_t>(l)] = chosen;
          apply(per_layer);
          const double error = rebuilt_squared_error(image, plan, params, tiles, passes, l, inverse_dwt, pool);
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
        per_layer[static_cast<std::size_t>(l)] = best;
      }
      apply(per_layer);
    } else {
      // Byte targets for the whole file: headers and packet headers included. Bisect a common
      // scale of the data budgets until the file fits its last target, as full as it gets.
      const auto target = static_cast<std::size_t>(params.layers.back().value);
      std::vector<std::vector<int>> none(static_cast<std::size_t>(layers), std::vector<int>(hulls.size(), 0));
      apply(none);
      const std::size_t overhead = assemble().size();
      if (overhead > target)
        throw EncodeError("the byte target " + std::to_string(target) + " is below the " + std::to_string(overhead) +
                          " bytes the headers alone take");
      auto plan_for = [&](double scale) {
        std::vector<std::size_t> budgets;
        for (const LayerTarget& t : params.layers)
          budgets.push_back(static_cast<std::size_t>(std::max(0.0, (t.value - static_cast<double>(overhead)) * scale)));
        return allocator.layers(budgets);
      };
      // Packet headers grow with the data, so the scale ends a little below 1. Stop once the file is
      // within 0.005 % of the target (or a few bytes): every byte left unspent is quality given
      // away, and a trial assembly costs little next to tier-1.
      double lo = 0, hi = 1.05;
      std::vector<std::vector<int>> best = none;
      std::size_t best_size = overhead;
      const std::size_t close_enough = target - std::max<std::size_t>(target / 20000, 4);
      for (int iteration = 0; iteration < 40 && best_size < close_enough; ++iteration) {
        const double mid = 0.5 * (lo + hi);
        const auto candidate = plan_for(mid);
        apply(candidate);
        const std::size_t size = assemble().size();
        if (size <= target) {
          lo = mid;
          if (size >= best_size) best_size = size, best = candidate;
        } else {
          hi = mid;
        }
      }
      apply(best);
    }
    // Pass skipping's check: a block that stopped early, and that the last layer now takes any
    // pass of its last coded bit-plane from, may have been stopped too soon. Code those in full
    // and allocate again; the rest stopped at least a whole bit-plane past the cut.
    std::vector<std::pair<std::size_t, std::size_t>> starved;  // (tile, block)
    for (std::size_t t = 0; t < tiles.size(); ++t)
      for (std::size_t b = 0; b < tiles[t].blocks.size(); ++b) {
        const t1::EncodedBlock& eb = tiles[t].blocks[b];
        // The last coded bit-plane's first pass: its cleanup when only the top plane was coded.
        const int coded = static_cast<int>(eb.passes.size());
        const int last_plane_start = coded == 1 ? 0 : coded - 3;
        if (eb.stopped_early && passes[t][b].back() > last_plane_start) starved.emplace_back(t, b);
      }
    if (!starved.empty() && recode_round < 2) {
      report.recoded_blocks += starved.size();
      const auto recode_start = Clock::now();
      pool.parallel_for(starved.size(), [&](std::size_t k) {
        CodedTile& tile = tiles[starved[k].first];
        const std::size_t b = starved[k].second;
        t1::EncodedBlock eb = code_block(tile, tile.jobs[b], params, tile.block_magnitude_bitplanes[b]);
        eb.missing_msbs = tile.blocks[b].missing_msbs;  // unchanged: the same bit-planes
        tile.blocks[b] = std::move(eb);
      });
      const double ms = since(recode_start);
      recode_ms += ms;
      report.times.tier1 += ms;
      continue;
    }
    break;
  }
  report.times.rate_control = since(rate_start) - recode_ms;
  const auto tier2_start = Clock::now();
  std::vector<std::uint8_t> bytes = assemble();
  report.times.tier2 = since(tier2_start);
  if (report_out) *report_out = std::move(report);
  return bytes;
}

}  // namespace

std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report) {
  return encode_image(image, nullptr, params, format, report);
}

std::vector<std::uint8_t> encode(SourceImage&& image, const EncodeParams& params, FileFormat format, EncodeReport* report) {
  // PSNR targets compare the rebuilt image with the source to the end, so they keep it.
  const bool needs_source = !params.layers.empty() && params.layers[0].kind == LayerTarget::Kind::Psnr;
  return encode_image(image, needs_source ? nullptr : &image, params, format, report);
}

}  // namespace codec
