#include "codec/encoder/tile_coder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <string>

#include "codec/encoder/component_transform.h"
#include "codec/encoder/encoder.h"
#include "dwt_gpu/gpu_backend.h"

#include <atomic>
#include <chrono>
#include "codec/encoder/quantization.h"
#include "dwt/norms.h"
#include "codec/structure/error.h"

namespace codec {
namespace {

int log2_exact(int v) { return std::countr_zero(static_cast<unsigned>(v)); }

// log2 of the nominal gain of each subband (T.800 Table E.1): 0 for LL, 1 for HL and LH, 2 for HH.
int band_gain(BandOrientation o) {
  switch (o) {
    case BandOrientation::LL: return 0;
    case BandOrientation::HH: return 2;
    default: return 1;
  }
}

t1::Orientation to_t1(BandOrientation o) { return static_cast<t1::Orientation>(static_cast<int>(o)); }

// Subbands in QCD order, LL first then HL, LH, HH from the coarsest level to the finest, which is
// also the order of resolutions 0..NL.
std::vector<BandOrientation> qcd_order(int levels) {
  std::vector<BandOrientation> out = {BandOrientation::LL};
  for (int i = 0; i < levels; ++i)
    for (auto o : {BandOrientation::HL, BandOrientation::LH, BandOrientation::HH}) out.push_back(o);
  return out;
}

int bits_for(std::int64_t magnitude) { return magnitude == 0 ? 0 : 64 - std::countl_zero(static_cast<std::uint64_t>(magnitude)); }

}  // namespace

std::size_t count_code_blocks(const CodingPlan& plan) {
  std::size_t total = 0;
  for (int t = 0; t < plan.grid.tile_count(); ++t) total += build_tile(plan.grid, plan.sampling, plan.styles, t).code_blocks;
  return total;
}

CodingPlan make_plan(const SourceImage& image, const EncodeParams& params) {
  validate(params);
  CodingPlan plan;
  ImageGrid& g = plan.grid;
  g.image = Rect{params.image_x0, params.image_y0, params.image_x0 + image.width, params.image_y0 + image.height};
  g.tile_x0 = params.tile_x0;
  g.tile_y0 = params.tile_y0;
  g.tile_width = params.tile_width > 0 ? params.tile_width : g.image.x1 - params.tile_x0;
  g.tile_height = params.tile_height > 0 ? params.tile_height : g.image.y1 - params.tile_y0;
  validate(g);

  CodingStyle style;
  style.levels = params.levels;
  style.xcb = log2_exact(params.codeblock_width);
  style.ycb = log2_exact(params.codeblock_height);
  if (!params.precincts.empty()) {
    // Finest resolution first on the command line; halve the last entry for coarser resolutions.
    style.precincts.resize(static_cast<std::size_t>(params.levels + 1));
    for (int r = params.levels, i = 0; r >= 0; --r, ++i) {
      const auto& given = params.precincts[static_cast<std::size_t>(std::min<int>(i, static_cast<int>(params.precincts.size()) - 1))];
      int ppx = log2_exact(given.first), ppy = log2_exact(given.second);
      const int extra = std::max(0, i - static_cast<int>(params.precincts.size()) + 1);
      const int floor_exp = r == 0 ? 0 : 1;
      ppx = std::max(floor_exp, ppx - extra);
      ppy = std::max(floor_exp, ppy - extra);
      style.precincts[static_cast<std::size_t>(r)] = {ppx, ppy};
    }
  }
  const std::size_t nc = image.components.size();
  plan.sampling.assign(nc, ComponentSampling{});
  plan.styles.assign(nc, style);
  const bool colour = nc >= 3 && image.components[0].precision == image.components[1].precision &&
                      image.components[1].precision == image.components[2].precision &&
                      image.components[0].is_signed == image.components[1].is_signed &&
                      image.components[1].is_signed == image.components[2].is_signed;
  plan.rct = params.lossless && colour;
  plan.ict = !params.lossless && colour;
  // Squared error in Y, Cb, Cr reaches R, G and B through the inverse ICT's columns (T.800 G-10).
  const double ict_weight[3] = {3.0, 0.34413 * 0.34413 + 1.772 * 1.772, 1.402 * 1.402 + 0.71414 * 0.71414};
  const dwt::Kernel& kernel97 = dwt::get_kernel(dwt::KernelId::Irreversible97);
  for (std::size_t c = 0; c < nc; ++c) {
    ComponentQuantization q;
    q.precision = image.components[c].precision + ((plan.rct && (c == 1 || c == 2)) ? 1 : 0);
    q.guard_bits = params.guard_bits >= 0 ? params.guard_bits : (params.lossless ? 2 : 1);
    if (plan.ict && c < 3) q.component_weight = ict_weight[c];
    int level = params.levels;  // LL first, then each level's three bands from the coarsest
    int in_level = 0;
    for (BandOrientation o : qcd_order(params.levels)) {
      const int range = q.precision + band_gain(o);  // R_b of E-3
      if (params.lossless) {
        q.exponents.push_back(range);
        continue;
      }
      const double norm = params.levels == 0 ? 1.0 : dwt::synthesis_norm(kernel97, std::max(level, 1), static_cast<dwt::Orientation>(static_cast<int>(o)));
      const StepSize step = encode_step(params.base_step * std::ldexp(1.0, q.precision) / norm, range);
      q.exponents.push_back(step.exponent);
      q.mantissas.push_back(step.mantissa);
      q.steps.push_back(step_value(step, range));
      q.norms.push_back(norm);
      if (o != BandOrientation::LL && ++in_level == 3) {
        in_level = 0;
        --level;
      }
    }
    plan.quantization.push_back(std::move(q));
  }
  return plan;
}

CodedTile code_tile(const SourceImage& image, const CodingPlan& plan, const EncodeParams& params, int tile_index,
                    dwt::DwtBackend& dwt, dwt::DwtBackend& reversible_dwt, dwt_cpu::ThreadPool& pool, StageTimes& times,
                    std::size_t progress_base, std::size_t progress_total) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
  auto clock = Clock::now();
  auto* gpu = dynamic_cast<dwt_gpu::GpuBackend*>(&dwt);
  CodedTile coded;
  coded.tile = build_tile(plan.grid, plan.sampling, plan.styles, tile_index);
  Tile& tile = coded.tile;
  const std::size_t nc = tile.components.size();

  // Samples of each tile-component, level shifted; then the component transform and the DWT into
  // the Mallat layout; lossy planes are quantised band by band into the same integer layout.
  std::vector<std::vector<std::int32_t>> planes(nc);
  std::vector<std::vector<float>> float_planes(params.lossless ? 0 : nc);
  std::vector<std::vector<std::uint8_t>> fractions(params.lossless ? 0 : nc);  // see quantize()
  for (std::size_t c = 0; c < nc; ++c) {
    const TileComponent& tc = tile.components[c];
    const auto w = static_cast<std::size_t>(tc.rect.width()), h = static_cast<std::size_t>(tc.rect.height());
    planes[c].resize(w * h);
    const SourceComponent& src = image.components[c];
    for (std::size_t y = 0; y < h; ++y) {
      const std::size_t sy = static_cast<std::size_t>(tc.rect.y0 - plan.grid.image.y0) + y;
      const std::size_t sx = static_cast<std::size_t>(tc.rect.x0 - plan.grid.image.x0);
      std::copy_n(src.samples.begin() + static_cast<std::ptrdiff_t>(sy * static_cast<std::size_t>(image.width) + sx), w,
                  planes[c].begin() + static_cast<std::ptrdiff_t>(y * w));
    }
    if (!src.is_signed) dc_shift_forward(planes[c], src.precision);
    if (!params.lossless) float_planes[c].assign(planes[c].begin(), planes[c].end());
  }
  if (plan.rct) rct_forward(planes[0], planes[1], planes[2]);
  if (plan.ict) ict_forward(float_planes[0], float_planes[1], float_planes[2]);
  times.level_shift += since(clock);

  for (std::size_t c = 0; c < nc; ++c) {
    const TileComponent& tc = tile.components[c];
    if (tc.rect.empty()) continue;
    const int w = static_cast<int>(tc.rect.width()), h = static_cast<int>(tc.rect.height());
    dwt::DwtParams p;
    p.kernel = params.lossless ? dwt::KernelId::Reversible53 : dwt::KernelId::Irreversible97;
    p.boundary = dwt::Boundary::Symmetric;
    p.levels = tc.levels;
    p.origin = dwt::Origin{tc.rect.x0, tc.rect.y0};
    p.levels_may_exceed_size = true;
    clock = Clock::now();
    if (params.lossless) {
      reversible_dwt.forward(dwt::make_span(planes[c].data(), w, h), p);
      times.dwt += since(clock);
      continue;
    }
    dwt.forward(dwt::make_span(float_planes[c].data(), w, h), p);
    if (gpu) {
      // The GPU splits its own time; anything around it (validation, tables) counts as upload.
      const dwt_gpu::GpuTimings& g = gpu->last_timings();
      const double whole = since(clock);
      times.dwt += g.compute_ms;
      times.download += g.download_ms;
      times.upload += whole - g.compute_ms - g.download_ms - g.context_ms - g.compile_ms;
      times.gl_context += g.context_ms;
      times.shader_compile += g.compile_ms;
    } else {
      times.dwt += since(clock);
    }
    clock = Clock::now();
    const ComponentQuantization& q = plan.quantization[c];
    fractions[c].assign(planes[c].size(), 0);
    int band_index = 0;
    for (const Resolution& res : tc.resolutions)
      for (const Subband& b : res.bands) {
        const auto inverse_step = static_cast<float>(1.0 / q.steps[static_cast<std::size_t>(band_index++)]);
        for (int y = 0; y < b.layout.height; ++y) {
          const std::size_t row = static_cast<std::size_t>(b.layout.y + y) * static_cast<std::size_t>(w) +
                                  static_cast<std::size_t>(b.layout.x);
          for (int x = 0; x < b.layout.width; ++x)
            planes[c][row + static_cast<std::size_t>(x)] =
                quantize(float_planes[c][row + static_cast<std::size_t>(x)], inverse_step, fractions[c][row + static_cast<std::size_t>(x)]);
        }
      }
    times.quantization += since(clock);
  }
  clock = Clock::now();

  // Guard bits: each component's coefficients must fit Mb = G + exponent - 1 magnitude bits.
  coded.guard_bits_needed.assign(nc, 0);
  for (std::size_t c = 0; c < nc; ++c) {
    const TileComponent& tc = tile.components[c];
    const ComponentQuantization& q = plan.quantization[c];
    int band_index = 0;
    for (const Resolution& res : tc.resolutions)
      for (const Subband& b : res.bands) {
        std::int64_t peak = 0;
        for (int y = 0; y < b.layout.height; ++y)
          for (int x = 0; x < b.layout.width; ++x)
            peak = std::max<std::int64_t>(peak, std::llabs(planes[c][static_cast<std::size_t>(b.layout.y + y) * static_cast<std::size_t>(tc.rect.width()) +
                                                                      static_cast<std::size_t>(b.layout.x + x)]));
        const int exponent = q.exponents[static_cast<std::size_t>(band_index++)];
        coded.guard_bits_needed[c] = std::max(coded.guard_bits_needed[c], bits_for(peak) - exponent + 1);
      }
    if (std::max(q.guard_bits, coded.guard_bits_needed[c]) > 7)
      throw EncodeError("component " + std::to_string(c) + "'s wavelet coefficients need more than 7 guard bits");
  }

  // Tier-1 on every code-block, in parallel. Mb is computed with the plan's guard bits; the caller
  // raises missing_msbs if some tile needed more (the coded bit-planes do not depend on Mb).
  struct Job {
    std::size_t component;
    const Subband* band;
    const CodeBlock* block;
    int exponent;
    int band_index;  // QCD order
  };
  std::vector<Job> jobs;
  for (std::size_t c = 0; c < nc; ++c) {
    const TileComponent& tc = tile.components[c];
    for (const Resolution& res : tc.resolutions) {
      const int first_band_index = res.r == 0 ? 0 : 1 + 3 * (res.r - 1);
      for (const Precinct& p : res.precincts)
        for (const PrecinctBand& pb : p.bands)
          for (const CodeBlock& cb : pb.blocks)
            jobs.push_back(Job{c, &res.bands[static_cast<std::size_t>(pb.band)], &cb,
                               plan.quantization[c].exponents[static_cast<std::size_t>(first_band_index + pb.band)],
                               first_band_index + pb.band});
    }
  }
  std::atomic<std::size_t> finished{0};
  coded.blocks.resize(tile.code_blocks);
  coded.block_weights.assign(tile.code_blocks, 1.0);
  coded.block_magnitude_bitplanes.assign(tile.code_blocks, 0);
  pool.parallel_for(jobs.size(), [&](std::size_t i) {
    const Job& job = jobs[i];
    const TileComponent& tc = tile.components[job.component];
    const ComponentQuantization& q = plan.quantization[job.component];
    const int guard = std::max(q.guard_bits, coded.guard_bits_needed[job.component]);
    const auto w = static_cast<int>(job.block->rect.width()), h = static_cast<int>(job.block->rect.height());
    thread_local std::vector<std::int32_t> buffer;
    buffer.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    thread_local std::vector<std::uint8_t> fraction_buffer;
    fraction_buffer.resize(params.lossless ? 0 : buffer.size());
    const std::int64_t x0 = job.band->layout.x + (job.block->rect.x0 - job.band->rect.x0);
    const std::int64_t y0 = job.band->layout.y + (job.block->rect.y0 - job.band->rect.y0);
    for (int y = 0; y < h; ++y)
      std::copy_n(planes[job.component].begin() + static_cast<std::ptrdiff_t>((y0 + y) * tc.rect.width() + x0), w,
                  buffer.begin() + static_cast<std::ptrdiff_t>(y) * w);
    if (!params.lossless)
      for (int y = 0; y < h; ++y)
        std::copy_n(fractions[job.component].begin() + static_cast<std::ptrdiff_t>((y0 + y) * tc.rect.width() + x0), w,
                    fraction_buffer.begin() + static_cast<std::ptrdiff_t>(y) * w);
    coded.block_magnitude_bitplanes[job.block->index] = guard + job.exponent - 1;
    t1::EncodedBlock eb = t1::encode_block(buffer, w, h, to_t1(job.band->orientation), guard + job.exponent - 1,
                                           params.block_style, fraction_buffer);
    eb.missing_msbs -= guard - q.guard_bits;  // expressed against the plan's guard bits for now
    coded.blocks[job.block->index] = std::move(eb);
    if (params.progress) params.progress(progress_base + finished.fetch_add(1) + 1, progress_total);
    if (!params.lossless) {
      const double step = q.steps[static_cast<std::size_t>(job.band_index)], norm = q.norms[static_cast<std::size_t>(job.band_index)];
      coded.block_weights[job.block->index] = step * step * norm * norm * q.component_weight;
    }
  });
  times.tier1 += since(clock);
  if (!params.lossless) coded.quantized = std::move(planes);
  return coded;
}

}  // namespace codec
