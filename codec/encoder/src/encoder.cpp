#include "codec/encoder/encoder.h"
#include "codec/encoder/engine.h"

#include <algorithm>

#include "codec/codestream/codestream_writer.h"
#include "codec/codestream/error.h"
#include "codec/codestream/jp2.h"
#include "codec/codestream/main_header.h"
#include "ht_rate.h"
#include "rate_control.h"
#include "tile_coder.h"
#include "codec/structure/error.h"
#include "codec/tier2/packet_writer.h"
#include "codec/tier2/progression.h"
#include "dwt_cpu/cpu_backend.h"
#include "codec/encoder/dwt_choice.h"

#include <chrono>
#include <optional>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace codec {
namespace {

// SPcod's code-block style with only bit 6 set: every code-block of the tile-component is an HT
// block (T.814 Table A.2); the EBCOT mode bits (0-5) stay clear.
constexpr std::uint8_t kHtBlockStyle = 0x40;

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
  h.cod.style.block_style = params.ht ? kHtBlockStyle : params.block_style.to_spcod();
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
                    [](const cs::StepSize& a, const cs::StepSize& b) {
                      return a.exponent == b.exponent && a.mantissa == b.mantissa;
                    }))
      h.qccs.push_back(cs::Qcc{static_cast<unsigned>(c), q});
  }
  if (!params.comment.empty()) h.comments.push_back(cs::latin_comment(params.comment));
  if (params.ht) {
    int largest_mb = 0;
    for (std::size_t c = 0; c < plan.quantization.size(); ++c)
      for (int e : plan.quantization[c].exponents) largest_mb = std::max(largest_mb, guard_bits[c] + e - 1);
    h.siz.rsiz = cs::kRsizCapabilitiesInCap;
    h.ccap15 = cs::ht_only_ccap15(!params.lossless, largest_mb);
  }
  return h;
}

t2::Order to_t2(Progression p) { return static_cast<t2::Order>(static_cast<int>(p)); }

// The guard bits the header states, per component: the plan's, or more where some tile's
// coefficients need them; every block's missing bit-planes are then counted against those.
std::vector<int> settle_guard_bits(std::vector<CodedTile>& tiles, const CodingPlan& plan) {
  std::vector<int> plan_guard;
  for (const auto& q : plan.quantization) plan_guard.push_back(q.guard_bits);
  std::vector<int> guard = plan_guard;
  for (const CodedTile& tile : tiles)
    for (std::size_t c = 0; c < guard.size(); ++c) guard[c] = std::max(guard[c], tile.guard_bits_needed[c]);
  for (CodedTile& coded : tiles)
    for (const TileComponent& tc : coded.tile.components)
      for (const Resolution& res : tc.resolutions)
        for (const Precinct& p : res.precincts)
          for (const PrecinctBand& pb : p.bands)
            for (const CodeBlock& cb : pb.blocks)
              coded.blocks[cb.index].missing_msbs +=
                  guard[static_cast<std::size_t>(tc.component)] - plan_guard[static_cast<std::size_t>(tc.component)];
  return guard;
}

// Pass skipping needs a target to predict from: each tile gets its share of the last layer's
// bytes (less a little for the headers), or of the squared error its PSNR allows (less a fifth:
// the rate-distortion estimate runs optimistic, so the PSNR loop aims below the goal). The
// prediction only sets where blocks stop, with a wide margin. None without targets.
// A tile's share of the image's samples.
double tile_share(const Tile& tile, double samples) {
  double tile_samples = 0;
  for (const TileComponent& tc : tile.components)
    tile_samples += static_cast<double>(tc.rect.width() * tc.rect.height());
  return tile_samples / std::max(1.0, samples);
}

// A tile's share of the code-block bytes a byte target of `bytes` leaves (the headers some 3 %).
Tier1Target tile_bytes(const Tile& tile, double bytes, double samples) {
  return {Tier1Target::Kind::Bytes, 0.97 * bytes * tile_share(tile, samples)};
}

Tier1Target tier1_target(const Tile& tile, const EncodeParams& params, double samples, double peak) {
  if (!params.skip_passes || params.lossless || params.layers.empty()) return {};
  const LayerTarget& last = params.layers.back();
  if (last.kind == LayerTarget::Kind::Bytes) return tile_bytes(tile, last.value, samples);
  const double share = tile_share(tile, samples);
  const double goal = samples * peak * peak * std::pow(10.0, -last.value / 10.0);
  return {Tier1Target::Kind::Distortion, 0.8 * goal * share};
}

// The most bits per coefficient (of the whole file's target) at which the step's phase is moved.
// Above it the phase gains little and can lose: the 16 photographs gained 0.023 dB on average at
// 3 bpp (1 bit) and 0.0003 dB at 4 bpp, the 2048x2048 mosaic lost 0.035 dB at 3 bpp, where at
// 2 bpp (0.67 bits) the photographs gained 0.056 dB.
constexpr double kHtPhaseMostBitsPerCoefficient = 0.8;

// The byte budget an HT encode's step phase aims at (ht_aligned_base_step): the tile's share of a
// single-layer byte target, as tier1_target gives it, with pass skipping on or off. Empty where the
// phase stays base_step's own: no HT, no byte target, several tiles (the QCD marker in the main
// header holds one base step for all), above kHtPhaseMostBitsPerCoefficient, or turned off.
std::optional<Tier1Target> ht_step_target(const Tile& tile, const EncodeParams& params, double samples, int tiles) {
  if (!params.ht || !params.ht_step_from_target || params.lossless || tiles != 1 || params.layers.size() != 1 ||
      params.layers.back().kind != LayerTarget::Kind::Bytes)
    return std::nullopt;
  const double bytes = params.layers.back().value;
  if (8 * bytes > kHtPhaseMostBitsPerCoefficient * samples) return std::nullopt;
  return tile_bytes(tile, bytes, samples);
}

// Tier-2's packet writer for precinct p of resolution res of tile-component tc, with the passes
// `passes[b]` lists for each block b (cumulative, after each layer).
// `ht_passes`: room for the pass counts of an HT block during rate control (the cleanup a trial
// picks, with its own passes), which the writer refers to; cleared and filled here, so it must
// stay untouched while the writer lives.
t2::PrecinctPacketWriter precinct_writer(const CodedTile& coded, const EncodeParams& params, const Precinct& p,
                                         const std::vector<std::vector<int>>& passes, std::vector<int>& ht_passes) {
  const bool ht_trial = !coded.ht_candidates.empty();
  if (ht_trial) {
    std::size_t counts = 0;
    for (const PrecinctBand& pb : p.bands)
      for (const CodeBlock& cb : pb.blocks) counts += passes[cb.index].size();
    ht_passes.assign(counts, 0);  // never reallocated below: the spans into it stay valid
  }
  std::size_t next_count = 0;
  std::vector<t2::PrecinctBand> bands;
  bands.reserve(p.bands.size());
  for (const PrecinctBand& pb : p.bands) {
    t2::PrecinctBand band;
    band.cols = pb.cols;
    band.rows = pb.rows;
    band.blocks.reserve(pb.blocks.size());
    for (const CodeBlock& cb : pb.blocks) {
      const std::vector<int>& cumulative = passes[cb.index];
      if (ht_trial) {
        const std::span<int> kept(ht_passes.data() + next_count, cumulative.size());
        next_count += cumulative.size();
        band.blocks.push_back(t2::CodeBlockCoding{&ht_packet_plan(coded, cb.index, cumulative, kept), kept});
        continue;
      }
      band.blocks.push_back(t2::CodeBlockCoding{&coded.blocks[cb.index], cumulative});
    }
    bands.push_back(std::move(band));
  }
  return t2::PrecinctPacketWriter(std::move(bands), params.block_style,
                                  params.ht ? t2::BlockCoder::Ht : t2::BlockCoder::Ebcot);
}

// The tile's precincts in (component, resolution, precinct) order.
std::vector<const Precinct*> tile_precincts(const Tile& tile) {
  std::vector<const Precinct*> precincts;
  for (const TileComponent& tc : tile.components)
    for (const Resolution& res : tc.resolutions)
      for (const Precinct& p : res.precincts) precincts.push_back(&p);
  return precincts;
}

// Indices into `precincts`, the largest (most code-blocks) first, so that no thread of a
// parallel loop over them is left with a big one at the end.
std::vector<std::size_t> largest_first(const std::vector<const Precinct*>& precincts) {
  auto blocks = [](const Precinct* p) {
    std::size_t n = 0;
    for (const PrecinctBand& pb : p->bands) n += pb.blocks.size();
    return n;
  };
  std::vector<std::size_t> order(precincts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return blocks(precincts[a]) > blocks(precincts[b]); });
  return order;
}

// Tier-2: every packet of the tile in progression order. `passes[b]` lists block b's cumulative
// passes after each layer. A precinct's packets depend only on its own earlier packets (its tag
// trees and block states), and each precinct's come in layer order in every progression, so the
// precincts write theirs in parallel, each packet into its own buffer with the sequence number of
// its place in the progression, and the buffers are joined in that order (on the H200 machine's
// 16 threads, writing them one after another took 1.5-2 ms for the 2048x2048 mosaic at 0.75 bpp
// and 4.5-7 ms for the 4096x4096 one).
std::vector<std::uint8_t> tile_body(const CodedTile& coded, const EncodeParams& params,
                                    const std::vector<std::vector<int>>& passes, int layers, base::ThreadPool& pool) {
  const Tile& tile = coded.tile;
  const std::vector<const Precinct*> precincts = tile_precincts(tile);
  std::vector<t2::ComponentGeometry> geometry;
  std::vector<std::vector<std::size_t>> first_precinct(tile.components.size());  // [component][resolution]
  std::size_t next = 0;
  for (const TileComponent& tc : tile.components) {
    t2::ComponentGeometry cg;
    for (const Resolution& res : tc.resolutions) {
      cg.resolutions.push_back(t2::ResolutionGeometry{res.rect.x0, res.rect.y0, res.rect.x1, res.rect.y1, res.ppx,
                                                      res.ppy, res.precincts_wide, res.precincts_high});
      first_precinct[static_cast<std::size_t>(tc.component)].push_back(next);
      next += res.precincts.size();
    }
    geometry.push_back(std::move(cg));
  }
  const auto layer_count = static_cast<std::size_t>(layers);
  const std::vector<t2::PacketId> order =
      t2::progression(to_t2(params.order), layers, tile.rect.x0, tile.rect.y0, tile.rect.x1, tile.rect.y1, geometry);
  auto packet_index = [&](const t2::PacketId& id) {
    const std::size_t precinct =
        first_precinct[static_cast<std::size_t>(id.component)][static_cast<std::size_t>(id.resolution)] +
        static_cast<std::size_t>(id.precinct);
    return precinct * layer_count + static_cast<std::size_t>(id.layer);
  };
  std::vector<std::uint16_t> sequence(precincts.size() * layer_count);  // SOP's Nsop, modulo 2^16
  for (std::size_t k = 0; k < order.size(); ++k) sequence[packet_index(order[k])] = static_cast<std::uint16_t>(k);
  std::vector<std::vector<std::uint8_t>> packets(precincts.size() * layer_count);
  const std::vector<std::size_t> work = largest_first(precincts);
  pool.parallel_for(work.size(), [&](std::size_t w) {
    const std::size_t i = work[w];
    std::vector<int> ht_passes;
    t2::PrecinctPacketWriter writer = precinct_writer(coded, params, *precincts[i], passes, ht_passes);
    for (std::size_t layer = 0; layer < layer_count; ++layer) {
      const std::size_t k = i * layer_count + layer;
      writer.write_packet(static_cast<int>(layer), params.sop, params.eph, sequence[k], packets[k], true);
    }
  });
  std::size_t bytes = 0;
  for (const std::vector<std::uint8_t>& packet : packets) bytes += packet.size();
  std::vector<std::uint8_t> body;
  body.reserve(bytes);
  for (const t2::PacketId& id : order) {
    const std::vector<std::uint8_t>& packet = packets[packet_index(id)];
    body.insert(body.end(), packet.begin(), packet.end());
  }
  return body;
}

// The length tile_body's packets would have, for rate control's trials: a packet's length does
// not depend on where the progression puts it (SOP's sequence number has a fixed size), so each
// precinct's packets are measured on their own, in parallel, their headers only.
std::size_t tile_packets_length(const CodedTile& coded, const EncodeParams& params,
                                const std::vector<std::vector<int>>& passes, int layers, base::ThreadPool& pool) {
  const std::vector<const Precinct*> precincts = tile_precincts(coded.tile);
  const std::vector<std::size_t> work = largest_first(precincts);
  std::vector<std::size_t> lengths(precincts.size());
  pool.parallel_for(work.size(), [&](std::size_t w) {
    const std::size_t i = work[w];
    thread_local std::vector<int> ht_passes;
    t2::PrecinctPacketWriter writer = precinct_writer(coded, params, *precincts[i], passes, ht_passes);
    thread_local std::vector<std::uint8_t> headers;
    for (int layer = 0; layer < layers; ++layer) {
      lengths[i] += writer.write_packet(layer, params.sop, params.eph, 0, headers, false);
      headers.clear();
    }
  });
  std::size_t total = 0;
  for (std::size_t length : lengths) total += length;
  return total;
}

// A resolution for a JP2 resolution box: none (both 0), or two values the box can hold, refused
// before any coding by the rule the box writer applies (cs::resolution_fraction).
void check_resolution(const GridResolution& r, const char* which) {
  if (r.vertical == 0 && r.horizontal == 0) return;
  try {
    cs::resolution_fraction(r.vertical);
    cs::resolution_fraction(r.horizontal);
  } catch (const cs::CodestreamError& e) {
    throw std::invalid_argument(std::string("the ") + which + " resolution: " + e.what());
  }
}

// The JP2/JPH header boxes' description of the image: SIZ's, with the resolutions asked for.
cs::Jp2Header jp2_header(const cs::Siz& siz, const EncodeParams& params) {
  cs::Jp2Header h = cs::jp2_header_for(siz);
  h.capture = cs::Jp2Resolution{params.capture_resolution.vertical, params.capture_resolution.horizontal};
  h.display = cs::Jp2Resolution{params.display_resolution.vertical, params.display_resolution.horizontal};
  return h;
}

// The codestream as the file `format` asks for: bare, or in a JP2 or JPH file's boxes.
std::vector<std::uint8_t> in_file(FileFormat format, std::vector<std::uint8_t> codestream, const cs::Siz& siz,
                                  const EncodeParams& params) {
  switch (format) {
    case FileFormat::Jp2:
      return cs::wrap_jp2(codestream, jp2_header(siz, params));
    case FileFormat::Jph:
      return cs::wrap_jph(codestream, jp2_header(siz, params));
    case FileFormat::Codestream:
      break;
  }
  return codestream;
}

std::vector<std::uint8_t> encode_image(const SourceImage& image, SourceImage* consumable, const EncodeParams& params,
                                       FileFormat format, EncodeReport* report_out) {
  // T.814 Annex D: the JPH brand promises an HTJ2K codestream.
  if (format == FileFormat::Jph && !params.ht)
    throw std::invalid_argument("a JPH (.jph) file holds an HTJ2K codestream: turn on HT coding (--ht)");
  check_resolution(params.capture_resolution, "capture");
  check_resolution(params.display_resolution, "display");
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  EncodeReport report;
  if (!params.lossless) report.base_step = params.base_step;
  // Stage 0: the plan, one set of worker threads for every stage, and where the DWT runs.
  const auto setup_start = Clock::now();
  CodingPlan plan = make_plan(image, params);
  std::optional<base::ThreadPool> own_pool;
  base::ThreadPool& pool = params.engine ? params.engine->pool() : own_pool.emplace(params.threads);
  report.threads = pool.size();
  double samples = 0;
  for (std::size_t c = 0; c < image.components.size(); ++c) samples += static_cast<double>(image.width) * image.height;
  DwtChoice dwt = choose_dwt(params, samples, pool);
  report.dwt_backend = dwt.name;
  report.dwt_reason = dwt.reason;
  report.times.gl_context = dwt.gl_context_ms;
  report.times.shader_compile = dwt.shader_compile_ms;
  std::optional<dwt_cpu::CpuBackend> reversible_dwt(std::in_place, pool);  // released before the pool

  int peak_bits = 0;
  for (const SourceComponent& c : image.components) peak_bits = std::max(peak_bits, c.precision);
  const double peak = std::ldexp(1.0, peak_bits) - 1;
  report.times.setup = since(setup_start) - report.times.gl_context - report.times.shader_compile;

  // Stages 1-4, tile by tile: samples in, level shift and component transform, DWT, quantisation
  // and tier-1.
  std::vector<CodedTile> tiles;
  const int count = plan.grid.tile_count();
  tiles.reserve(static_cast<std::size_t>(count));
  const std::size_t all_blocks = params.progress ? count_code_blocks(plan) : 0;
  std::size_t blocks_before = 0;
  for (int t = 0; t < count; ++t) {
    // Stages 1-2, then (HT under a byte target) the step's phase, then stages 3-4 at that step.
    CodedTile coded =
        transform_tile(image, consumable, plan, params, t, *dwt.backend, *reversible_dwt, pool, report.times);
    if (const std::optional<Tier1Target> bytes = ht_step_target(coded.tile, params, samples, count)) {
      const auto clock = Clock::now();
      if (const std::optional<double> step = ht_aligned_base_step(coded, plan, params, *bytes, pool)) {
        EncodeParams aligned = params;
        aligned.base_step = *step;
        plan = make_plan(image, aligned);
        report.base_step = *step;
      }
      report.times.tier1 += since(clock);
    }
    code_tile_blocks(coded, plan, params, pool, report.times, tier1_target(coded.tile, params, samples, peak),
                     blocks_before, all_blocks);
    tiles.push_back(std::move(coded));
    blocks_before += tiles.back().blocks.size();
  }
  const std::vector<int> guard_bits = settle_guard_bits(tiles, plan);

  // Stage 5: rate control, choosing each layer's passes; without targets every pass in one layer.
  const int layers = params.layers.empty() ? 1 : static_cast<int>(params.layers.size());
  const cs::MainHeader header = main_header(image, params, plan, guard_bits, layers);
  const Assembler assemble = [&](const LayerPasses& passes) {
    cs::CodestreamWriter writer(header);
    for (std::size_t t = 0; t < tiles.size(); ++t)
      writer.add_tile_part(static_cast<unsigned>(tiles[t].tile.index), 0, 1,
                           tile_body(tiles[t], params, passes[t], layers, pool));
    std::vector<std::uint8_t> codestream = writer.finish();
    return in_file(format, std::move(codestream), header.siz, params);
  };
  // Rate control's trial files: the main header, each tile-part's SOT and SOD, EOC and any JP2
  // boxes do not depend on the selection, so they are measured once with empty tile bodies, and a
  // trial adds its packets' lengths, counted without copying the data.
  const std::size_t fixed_bytes = [&] {
    cs::CodestreamWriter writer(header);
    for (const CodedTile& tile : tiles) writer.add_tile_part(static_cast<unsigned>(tile.tile.index), 0, 1, {});
    const std::vector<std::uint8_t> codestream = writer.finish();
    return in_file(format, codestream, header.siz, params).size();
  }();
  const FileSizer file_size = [&](const LayerPasses& trial) {
    std::size_t bytes = fixed_bytes;
    for (std::size_t t = 0; t < tiles.size(); ++t)
      bytes += tile_packets_length(tiles[t], params, trial[t], layers, pool);
    // A JP2 codestream box past 4 GiB takes a longer header: measure such a file whole.
    return bytes < 0xFFFF0000u ? bytes : assemble(trial).size();
  };
  const LayerPasses passes =
      params.layers.empty()
          ? every_pass(tiles, layers)
          : control_rate(tiles, RateControlInputs{image, plan, params, samples, peak, pool}, file_size, report);

  // Stage 6: tier-2 and the codestream.
  const auto tier2_start = Clock::now();
  std::vector<std::uint8_t> bytes = assemble(passes);
  report.times.tier2 = since(tier2_start);

  // Stage 7: the memory, the DWT backend (a GL context made for this image) and the worker threads
  // handed back, timed so that the stages account for the whole encode.
  const auto release_start = Clock::now();
  discard_coefficient_planes(tiles, pool);
  tiles = {};
  if (consumable != nullptr) {
    // Given up by the caller, who keeps its size and components.
    for (SourceComponent& c : consumable->components) c.samples = {};
    consumable->packed.reset();
  }
  dwt.backend.reset();
  reversible_dwt.reset();
  own_pool.reset();
  report.times.release = since(release_start);
  if (report_out) *report_out = std::move(report);
  return bytes;
}

}  // namespace

std::vector<std::uint8_t> encode(const SourceImage& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report) {
  return encode_image(image, nullptr, params, format, report);
}

std::vector<std::uint8_t> encode(SourceImage&& image, const EncodeParams& params, FileFormat format,
                                 EncodeReport* report) {
  // PSNR targets compare the rebuilt image with the source to the end, so they keep it.
  const bool needs_source = !params.layers.empty() && params.layers[0].kind == LayerTarget::Kind::Psnr;
  return encode_image(image, needs_source ? nullptr : &image, params, format, report);
}

}  // namespace codec
