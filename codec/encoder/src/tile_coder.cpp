#include "tile_coder.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <string>

#include "component_transform.h"
#include "component_transform_simd.h"
#include "ht_rate.h"
#include "codec/ht/ht_block_encoder.h"
#include "codec/encoder/encoder.h"
#include "quantization.h"
#include "codec/rate/hull.h"
#include "codec/rate/selection.h"
#include "codec/structure/error.h"
#include "dwt/norms.h"
#include "imageio/plane_memory.h"

namespace codec {
namespace {

int log2_exact(int v) { return std::countr_zero(static_cast<unsigned>(v)); }

// Tier-1 names the orientations itself (it depends on no wavelet code); the values are T.800's.
static_assert(static_cast<int>(t1::Orientation::LL) == static_cast<int>(BandOrientation::LL) &&
                  static_cast<int>(t1::Orientation::HL) == static_cast<int>(BandOrientation::HL) &&
                  static_cast<int>(t1::Orientation::LH) == static_cast<int>(BandOrientation::LH) &&
                  static_cast<int>(t1::Orientation::HH) == static_cast<int>(BandOrientation::HH),
              "tier-1's orientations are the subbands'");
t1::Orientation to_t1(BandOrientation o) { return static_cast<t1::Orientation>(static_cast<int>(o)); }

// Subbands in QCD order, LL first then HL, LH, HH from the coarsest level to the finest, which is
// also the order of resolutions 0..NL.
std::vector<BandOrientation> qcd_order(int levels) {
  std::vector<BandOrientation> out = {BandOrientation::LL};
  for (int i = 0; i < levels; ++i)
    for (auto o : {BandOrientation::HL, BandOrientation::LH, BandOrientation::HH}) out.push_back(o);
  return out;
}

}  // namespace

std::size_t count_code_blocks(const CodingPlan& plan) {
  std::size_t total = 0;
  for (int t = 0; t < plan.grid.tile_count(); ++t)
    total += build_tile(plan.grid, plan.sampling, plan.styles, t).code_blocks;
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
      const auto& given =
          params.precincts[static_cast<std::size_t>(std::min<int>(i, static_cast<int>(params.precincts.size()) - 1))];
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
      const double norm = params.levels == 0 ? 1.0 : dwt::synthesis_norm(kernel97, std::max(level, 1), o);
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

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// Rows of a plane in chunks of this many, one pool item each: large enough to amortise the
// hand-out, small enough to balance two to sixteen threads.
constexpr std::size_t kRowsPerItem = 16;

// Calls rows(y0, y1) for consecutive chunks of [0, height) on the pool.
template <class Rows>
void for_row_chunks(base::ThreadPool& pool, std::size_t height, Rows&& rows) {
  pool.parallel_for((height + kRowsPerItem - 1) / kRowsPerItem,
                    [&](std::size_t item) { rows(item * kRowsPerItem, std::min(height, (item + 1) * kRowsPerItem)); });
}

// Stage 1: each tile-component's samples, DC level shifted (T.800 G.1.2) and, for three equal
// components, through the RCT or ICT (G.2, G.3), in one pass over the source, by row chunks.
// Lossless planes are integers; lossy ones floats, ready for the 9/7.
struct TilePlanes {
  std::vector<imageio::SamplePlane> integers;  // lossless
  std::vector<FloatPlane> floats;              // lossy
};

// Whether a lossless tile can take the source's planes and transform them where they are: the
// caller gave the image up, and the tile covers every component whole.
bool can_take_source(const SourceImage* consumable, const CodingPlan& plan, const Tile& tile) {
  if (consumable == nullptr || consumable->packed) return false;
  for (std::size_t c = 0; c < tile.components.size(); ++c) {
    const Rect& r = tile.components[c].rect;
    if (r.x0 != plan.grid.image.x0 || r.y0 != plan.grid.image.y0 || r.width() != consumable->width ||
        r.height() != consumable->height ||
        consumable->components[c].samples.size() != static_cast<std::size_t>(r.width() * r.height()))
      return false;
  }
  return true;
}

// Gives rows [y0, y1) of a source component given up by the caller back to the system: the pages
// wholly inside them are dropped (they would read as zeros, and nothing reads them again), so the
// image's memory shrinks as its rows are converted.
void release_rows(SourceImage& image, std::size_t component, std::size_t y0, std::size_t y1) {
  imageio::SamplePlane& samples = image.components[component].samples;
  const auto w = static_cast<std::size_t>(image.width);
  imageio::discard_pages(samples.data() + y0 * w, (y1 - y0) * w * sizeof(samples[0]));
}

TilePlanes load_tile_planes(const SourceImage& image, SourceImage* consumable, const CodingPlan& plan, const Tile& tile,
                            bool lossless, base::ThreadPool& pool) {
  const std::size_t nc = tile.components.size();
  TilePlanes out;
  (lossless ? out.integers.resize(nc) : out.floats.resize(nc));
  // In place: the shift and RCT read each sample before writing it, so the source rows below can
  // be the output rows themselves.
  const bool in_place = lossless && can_take_source(consumable, plan, tile);
  // Lossy, with a source given up: its float planes are new memory, but each chunk of source rows
  // goes back to the system as soon as it is converted, so the two never both hold the image.
  const bool release_source = !lossless && can_take_source(consumable, plan, tile);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t n = static_cast<std::size_t>(tile.components[c].rect.width()) *
                          static_cast<std::size_t>(tile.components[c].rect.height());
    if (in_place)
      out.integers[c] = std::move(consumable->components[c].samples);
    else
      lossless ? imageio::resize_with_huge_pages(out.integers[c], n)
               : imageio::resize_with_huge_pages(out.floats[c], n);
  }
  const bool mct = plan.rct || plan.ict;
  const TileComponent& first = tile.components[0];
  const auto w = static_cast<std::size_t>(first.rect.width()), h = static_cast<std::size_t>(first.rect.height());
  // Row y of tile-component c: in the plane it is transformed in, in the source's plane, or
  // unpacked from a packed source into `scratch` (room for the row).
  auto source_row = [&](std::size_t c, std::size_t y, std::int32_t* scratch) {
    const TileComponent& tc = tile.components[c];
    const std::size_t sy = static_cast<std::size_t>(tc.rect.y0 - plan.grid.image.y0) + y;
    const std::size_t sx = static_cast<std::size_t>(tc.rect.x0 - plan.grid.image.x0);
    if (in_place)
      return static_cast<const std::int32_t*>(out.integers[c].data() + sy * static_cast<std::size_t>(image.width) + sx);
    return codec::source_row(image, c, sy, sx, static_cast<std::size_t>(tc.rect.width()), scratch);
  };
  auto shift_of = [&](std::size_t c) {
    const SourceComponent& src = image.components[c];
    return src.is_signed ? 0 : std::int32_t{1} << (src.precision - 1);
  };
  // Rows [y0, y1) of new plane c, `width` samples each, faulted in at once rather than store by
  // store as they are written (a 4096x4096 RGB image's planes are 192 MiB of new pages: 15-20 ms
  // less on 2 vCPUs).
  auto populate_rows = [&](std::size_t c, std::size_t width, std::size_t y0, std::size_t y1) {
    if (in_place) return;
    if (lossless)
      imageio::populate_for_writing(out.integers[c].data() + y0 * width, (y1 - y0) * width * sizeof(std::int32_t));
    else
      imageio::populate_for_writing(out.floats[c].data() + y0 * width, (y1 - y0) * width * sizeof(float));
  };
  // The component transform's three components share one geometry (make_plan checks it).
  if (mct) {
    const std::int32_t s0 = shift_of(0), s1 = shift_of(1), s2 = shift_of(2);
    // An 8-bit RGB raster as the file held it goes through the transform straight from its bytes.
    const imageio::PackedImage* rgb8 =
        image.packed && image.packed->channels == 3 && image.packed->bytes_per_sample == 1 ? image.packed.get()
                                                                                           : nullptr;
    for_row_chunks(pool, h, [&](std::size_t y0, std::size_t y1) {
      for (std::size_t c = 0; c < 3; ++c) populate_rows(c, w, y0, y1);
      std::vector<std::int32_t> scratch(image.packed && !rgb8 ? 3 * w : 0);
      for (std::size_t y = y0; y < y1; ++y) {
        if (rgb8) {
          const std::size_t sy = static_cast<std::size_t>(first.rect.y0 - plan.grid.image.y0) + y;
          const std::size_t sx = static_cast<std::size_t>(first.rect.x0 - plan.grid.image.x0);
          const std::uint8_t* pixels = rgb8->raster + sy * rgb8->row_bytes() + 3 * sx;
          if (lossless)
            simd::rct_forward_rgb8_row(pixels, s0, s1, s2, out.integers[0].data() + y * w,
                                       out.integers[1].data() + y * w, out.integers[2].data() + y * w, w);
          else
            simd::ict_forward_rgb8_row(pixels, s0, s1, s2, out.floats[0].data() + y * w, out.floats[1].data() + y * w,
                                       out.floats[2].data() + y * w, w);
          continue;
        }
        // Component c's room in the scratch row; none (null, not an offset from null) when the
        // source is planar and rows are read where they lie.
        auto room = [&](std::size_t c) { return scratch.empty() ? nullptr : scratch.data() + c * w; };
        const std::int32_t *r = source_row(0, y, room(0)), *g = source_row(1, y, room(1)),
                           *b = source_row(2, y, room(2));
        if (lossless) {
          rct_forward_row(r, g, b, s0, s1, s2, out.integers[0].data() + y * w, out.integers[1].data() + y * w,
                          out.integers[2].data() + y * w, w);
        } else {
          ict_forward_row(r, g, b, s0, s1, s2, out.floats[0].data() + y * w, out.floats[1].data() + y * w,
                          out.floats[2].data() + y * w, w);
        }
      }
      if (release_source)
        for (std::size_t c = 0; c < 3; ++c) release_rows(*consumable, c, y0, y1);
    });
  }
  for (std::size_t c = mct ? 3 : 0; c < nc; ++c) {
    const TileComponent& tc = tile.components[c];
    const auto cw = static_cast<std::size_t>(tc.rect.width()), ch = static_cast<std::size_t>(tc.rect.height());
    const std::int32_t shift = shift_of(c);
    for_row_chunks(pool, ch, [&](std::size_t y0, std::size_t y1) {
      populate_rows(c, cw, y0, y1);
      std::vector<std::int32_t> scratch(image.packed ? cw : 0);
      for (std::size_t y = y0; y < y1; ++y) {
        const std::int32_t* src = source_row(c, y, scratch.data());
        if (lossless)
          for (std::size_t x = 0; x < cw; ++x) out.integers[c][y * cw + x] = src[x] - shift;
        else
          for (std::size_t x = 0; x < cw; ++x) out.floats[c][y * cw + x] = static_cast<float>(src[x] - shift);
      }
      if (release_source) release_rows(*consumable, c, y0, y1);
    });
  }
  if (release_source)
    for (SourceComponent& component : consumable->components) imageio::SamplePlane().swap(component.samples);
  return out;
}

dwt::DwtParams dwt_params(const TileComponent& tc, bool lossless) {
  dwt::DwtParams p;
  p.kernel = lossless ? dwt::KernelId::Reversible53 : dwt::KernelId::Irreversible97;
  p.boundary = dwt::Boundary::Symmetric;
  p.levels = tc.levels;
  p.origin = dwt::Origin{tc.rect.x0, tc.rect.y0};
  p.levels_may_exceed_size = true;
  return p;
}

// Stage 2: the forward DWT of every tile-component, into the Mallat layout, in place.
void transform_planes(const Tile& tile, TilePlanes& planes, bool lossless, dwt::DwtBackend& dwt,
                      dwt::DwtBackend& reversible_dwt, StageTimes& times) {
  for (std::size_t c = 0; c < tile.components.size(); ++c) {
    const TileComponent& tc = tile.components[c];
    if (tc.rect.empty()) continue;
    const int w = static_cast<int>(tc.rect.width()), h = static_cast<int>(tc.rect.height());
    const auto clock = Clock::now();
    if (lossless) {
      reversible_dwt.forward(dwt::make_span(planes.integers[c].data(), w, h), dwt_params(tc, true));
      times.dwt += ms_since(clock);
      continue;
    }
    dwt.forward(dwt::make_span(planes.floats[c].data(), w, h), dwt_params(tc, false));
    if (const dwt::DeviceTimings* device = dwt.device_timings()) {
      // A device splits its own time; anything around it (validation, tables) counts as upload.
      const dwt::DeviceTimings& g = *device;
      const double whole = ms_since(clock);
      times.dwt += g.compute_ms;
      times.download += g.download_ms;
      times.upload += whole - g.compute_ms - g.download_ms - g.context_ms - g.compile_ms;
      times.gl_context += g.context_ms;
      times.shader_compile += g.compile_ms;
    } else {
      times.dwt += ms_since(clock);
    }
  }
}

// After tier-1: the guard bits each component needs so that its coefficients fit
// Mb = G + exponent - 1 magnitude bits (T.800 E-2), from the bit-planes every block uses.
void find_guard_bits(const Tile& tile, const CodingPlan& plan, CodedTile& coded) {
  const std::size_t nc = tile.components.size();
  coded.guard_bits_needed.assign(nc, 0);
  for (const BlockJob& job : coded.jobs) {
    const int planes = coded.blocks[job.block_index].bit_planes;
    int& needed = coded.guard_bits_needed[job.component];
    needed = std::max(needed, planes - job.exponent + 1);
  }
  for (std::size_t c = 0; c < nc; ++c)
    if (std::max(plan.quantization[c].guard_bits, coded.guard_bits_needed[c]) > 7)
      throw EncodeError("component " + std::to_string(c) + "'s wavelet coefficients need more than 7 guard bits");
  // Mb and the missing bit-planes, against the plan's guard bits (the encoder raises them to the
  // guard bits of the whole image later; the coded bit-planes do not depend on Mb).
  for (const BlockJob& job : coded.jobs) {
    const int plan_guard = plan.quantization[job.component].guard_bits;
    const int guard = std::max(plan_guard, coded.guard_bits_needed[job.component]);
    coded.block_magnitude_bitplanes[job.block_index] = guard + job.exponent - 1;
    t1::EncodedBlock& eb = coded.blocks[job.block_index];
    eb.missing_msbs = plan_guard + job.exponent - 1 - eb.bit_planes + eb.first_pass_planes - 1;
  }
}

// Stage 4's work list: every code-block of the tile, indexed by CodeBlock::index (which build_tile
// numbers in (component, resolution, precinct, band) order), with what tier-1 and rate control
// need to know of it.
std::vector<BlockJob> block_jobs(const Tile& tile, const CodingPlan& plan, bool lossless) {
  std::vector<BlockJob> jobs(tile.code_blocks);
  for (std::size_t c = 0; c < tile.components.size(); ++c) {
    const TileComponent& tc = tile.components[c];
    const ComponentQuantization& q = plan.quantization[c];
    for (const Resolution& res : tc.resolutions) {
      const int first_band_index = res.r == 0 ? 0 : 1 + 3 * (res.r - 1);
      for (const Precinct& p : res.precincts)
        for (const PrecinctBand& pb : p.bands)
          for (const CodeBlock& cb : pb.blocks) {
            const Subband& band = res.bands[static_cast<std::size_t>(pb.band)];
            const auto band_index = static_cast<std::size_t>(first_band_index + pb.band);
            BlockJob job;
            job.component = c;
            job.block_index = cb.index;
            job.resolution = res.r;
            job.orientation = to_t1(band.orientation);
            job.x0 = band.layout.x + (cb.rect.x0 - band.rect.x0);
            job.y0 = band.layout.y + (cb.rect.y0 - band.rect.y0);
            job.width = static_cast<int>(cb.rect.width());
            job.height = static_cast<int>(cb.rect.height());
            job.plane_width = tc.rect.width();
            job.exponent = q.exponents[band_index];
            if (!lossless) {
              const double step = q.steps[band_index], norm = q.norms[band_index];
              job.weight = step * step * norm * norm * q.component_weight;
              job.inverse_step = static_cast<float>(1.0 / step);
              job.step = static_cast<float>(step);
            }
            jobs[cb.index] = job;
          }
    }
  }
  return jobs;
}

}  // namespace

void discard_coefficient_planes(std::vector<CodedTile>& tiles, base::ThreadPool& pool) {
  // Chunks of 4 MiB: a few dozen per 4096x4096 plane, enough to keep sixteen threads busy.
  constexpr std::size_t kChunkBytes = std::size_t{4} << 20;
  struct Chunk {
    const std::uint8_t* data;
    std::size_t bytes;
  };
  std::vector<Chunk> chunks;
  auto add = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    for (std::size_t at = 0; at < bytes; at += kChunkBytes)
      chunks.push_back({p + at, std::min(kChunkBytes, bytes - at)});
  };
  for (const CodedTile& coded : tiles) {
    for (const auto& plane : coded.quantized) add(plane.data(), plane.size() * sizeof(plane[0]));
    for (const auto& plane : coded.coefficients) add(plane.data(), plane.size() * sizeof(plane[0]));
  }
  pool.parallel_for(chunks.size(), [&](std::size_t k) { imageio::discard_pages(chunks[k].data, chunks[k].bytes); });
}

// Stratified by resolution (their blocks differ most in value: a coarse block is worth many fine
// ones): resolutions with few blocks are taken whole, the others one block in `stride`, each
// standing for its resolution's coefficients over those of its sampled blocks.
BlockSample sample_blocks(const std::vector<BlockJob>& jobs, std::size_t stride, std::size_t most, bool scattered) {
  int resolutions = 0;
  for (const BlockJob& j : jobs) resolutions = std::max(resolutions, j.resolution + 1);
  std::vector<double> coefficients(static_cast<std::size_t>(resolutions)), sampled(coefficients.size());
  std::vector<std::size_t> blocks(coefficients.size()), seen(coefficients.size());
  for (const BlockJob& j : jobs) {
    coefficients[static_cast<std::size_t>(j.resolution)] += static_cast<double>(j.width) * j.height;
    ++blocks[static_cast<std::size_t>(j.resolution)];
  }
  std::vector<std::size_t> strides(blocks.size());
  for (std::size_t r = 0; r < blocks.size(); ++r) strides[r] = std::max(stride, (blocks[r] + most - 1) / most);
  BlockSample out;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const auto r = static_cast<std::size_t>(jobs[i].resolution);
    const std::size_t place = seen[r]++;
    // Fibonacci hashing: the top 24 bits of place * 2^32 / phi, uniform enough for a sample.
    const auto hash = static_cast<std::uint32_t>(place * 0x9E3779B1u) >> 8;
    const bool taken = scattered ? hash % strides[r] == 0 : place % strides[r] == 0;
    if (blocks[r] <= kWholeResolutionBlocks || taken) {
      out.blocks.push_back(i);
      sampled[r] += static_cast<double>(jobs[i].width) * jobs[i].height;
    }
  }
  for (std::size_t i : out.blocks) {
    const auto r = static_cast<std::size_t>(jobs[i].resolution);
    out.scale.push_back(coefficients[r] / sampled[r]);
  }
  return out;
}

// Predicts the final slope threshold from a sample of blocks coded (in full wherever the hulls are
// looked at): the threshold at which the sample, scaled up, spends the tile's bytes, or leaves the
// tile's squared error.
double threshold_for_target(std::span<const std::vector<rate::HullPoint>> hulls, std::span<const double> scale,
                            double energy, const Tier1Target& target) {
  // Bytes spent, and squared error left, by the whole tile at a threshold, as the hulls tell.
  auto at = [&](double threshold) {
    double bytes = 0, kept = 0;
    for (std::size_t k = 0; k < hulls.size(); ++k) {
      const std::size_t points = rate::points_at_or_above(hulls[k], threshold);
      if (points > 0)
        bytes += scale[k] * static_cast<double>(hulls[k][points - 1].bytes),
            kept += scale[k] * hulls[k][points - 1].distortion;
    }
    return std::pair{bytes, energy - kept};
  };
  // Bisect on the logarithm: slopes span many decades. Both bytes and error are monotone in it.
  double lo = -60, hi = 60;  // log2 of the threshold
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const auto [bytes, error] = at(std::exp2(mid));
    const bool too_much = target.kind == Tier1Target::Kind::Bytes ? bytes > target.value : error < target.value;
    (too_much ? lo : hi) = mid;
  }
  return std::exp2(hi);
}

double predict_threshold(const std::vector<BlockJob>& jobs, const CodedTile& coded, const BlockSample& sample,
                         const Tier1Target& target) {
  std::vector<std::vector<rate::HullPoint>> hulls;
  double energy = 0;
  for (std::size_t k = 0; k < sample.blocks.size(); ++k) {
    const BlockJob& j = jobs[sample.blocks[k]];
    hulls.push_back(rate::convex_hull(coded.blocks[j.block_index].passes, j.weight));
    energy += sample.scale[k] * coded.blocks[j.block_index].energy * j.weight;
  }
  return threshold_for_target(hulls, sample.scale, energy, target);
}

namespace {

// How many of their top bit-planes the presample's blocks are first coded to, for a byte target of
// `bits_per_coefficient`; 0: none, the presample is coded in full at once. The fewer the bytes, the
// fewer planes survive, and the more of a full coding is wasted. On the 2048x2048 mosaic the
// presample took 13-15 ms of 2 threads' tier-1 in full; the top 3 planes and then down to an eighth
// of what they predict, 7 ms at 0.1875 bpp (0.0625 bits per coefficient), where 4 planes took 9;
// 4 planes, 11 ms at 0.75 bpp (0.25 bits), where 3 planes took 12; and every depth tried (3 to 6
// planes) cost more than coding in full at 3 bpp (1 bit), 17-19 ms. The files are the same.
int presample_top_planes(const Tier1Target& target, double bits_per_coefficient) {
  if (target.kind != Tier1Target::Kind::Bytes) return 0;
  if (bits_per_coefficient <= 0.1) return 3;
  if (bits_per_coefficient <= 0.35) return 4;
  return 0;
}

// The blocks of `which` that stopped before their last pass.
std::vector<std::size_t> stopped_blocks(const CodedTile& coded, const std::vector<std::size_t>& which) {
  std::vector<std::size_t> stopped;
  for (std::size_t i : which)
    if (coded.blocks[coded.jobs[i].block_index].stopped_early) stopped.push_back(i);
  return stopped;
}

// Codes the blocks of `sample` (sample_blocks with kSampleStride) and returns the slope threshold
// they predict. In two steps: a sparser sample coded deep enough gives a first estimate, the rest
// of the sample stops far below it (its hulls are then whole wherever the prediction looks), and
// the blocks that stopped are coded in full after all if the prediction falls within reach of where
// they stopped. `run(blocks, stop)` codes the listed blocks of `coded`.
//
// "Deep enough" is in full, or, at low rates, below a floor: the presample's top few bit-planes
// alone predict a threshold no higher than the full coding's (fewer passes spend fewer bytes, and
// leave more error, at every threshold), and the presample then stops an eighth below that floor.
// Where the first estimate does not come out at or above the floor (hulls can defy that in
// principle), the stopped blocks are coded in full and the estimate is made again, as without it.
template <class Run>
double code_sample(CodedTile& coded, const BlockSample& sample, const Tier1Target& target, Run&& run) {
  const BlockSample presample = sample_blocks(coded.jobs, kPresampleStride);
  std::vector<bool> in_presample(coded.jobs.size());
  for (std::size_t i : presample.blocks) in_presample[i] = true;
  std::vector<std::size_t> sample_rest;
  for (std::size_t i : sample.blocks)
    if (!in_presample[i]) sample_rest.push_back(i);

  double coefficients = 0;
  for (const BlockJob& j : coded.jobs) coefficients += static_cast<double>(j.width) * j.height;
  const int top_planes = presample_top_planes(target, 8 * target.value / std::max(coefficients, 1.0));
  double first_estimate = 0;
  if (top_planes > 0) {
    run(presample.blocks, t1::StopRule{0, 1, 3 * top_planes - 2});
    const double floor = predict_threshold(coded.jobs, coded, presample, target);
    run(presample.blocks, t1::StopRule{floor / kPresampleMargin, 1});
    first_estimate = predict_threshold(coded.jobs, coded, presample, target);
    if (first_estimate < floor) {
      run(stopped_blocks(coded, presample.blocks), t1::StopRule{});
      first_estimate = predict_threshold(coded.jobs, coded, presample, target);
    }
  } else {
    run(presample.blocks, t1::StopRule{});
    first_estimate = predict_threshold(coded.jobs, coded, presample, target);
  }
  run(sample_rest, t1::StopRule{first_estimate / kPresampleMargin, 1});
  double predicted = predict_threshold(coded.jobs, coded, sample, target);
  // Every stopped block of the sample stopped at or below first_estimate / kPresampleMargin.
  if (predicted < first_estimate / (kPresampleMargin / 2)) {
    run(stopped_blocks(coded, sample.blocks), t1::StopRule{});
    predicted = predict_threshold(coded.jobs, coded, sample, target);
  }
  return predicted;
}

std::ptrdiff_t block_offset(const BlockJob& job) {
  return static_cast<std::ptrdiff_t>(job.y0 * job.plane_width + job.x0);
}

// A block of a lossless tile's kept integers, where they lie in its plane.
t1::IntegerBlock integer_block(const CodedTile& coded, const BlockJob& job) {
  return t1::IntegerBlock{coded.quantized[job.component].data() + block_offset(job),
                          static_cast<std::ptrdiff_t>(job.plane_width), job.width, job.height};
}

}  // namespace

void load_ht_block(const CodedTile& coded, const BlockJob& job, const EncodeParams& params, ht::HtBlock& into) {
  if (params.lossless) return ht::load_ht_block(integer_block(coded, job), into);
  ht::load_ht_block(float_block(coded, job), into);
}

t1::FloatBlock float_block(const CodedTile& coded, const BlockJob& job) {
  return t1::FloatBlock{coded.coefficients[job.component].data() + block_offset(job),
                        static_cast<std::ptrdiff_t>(job.plane_width), job.width, job.height, job.inverse_step};
}

t1::EncodedBlock code_block(const CodedTile& coded, const BlockJob& job, const EncodeParams& params,
                            int magnitude_bitplanes, t1::StopRule stop) {
  stop.weight = job.weight;
  // Only rate control reads the passes' distortion: with every pass kept it need not be measured.
  const t1::Distortion distortion = params.layers.empty() ? t1::Distortion::Skipped : t1::Distortion::Measured;
  if (params.ht && params.lossless)
    return ht::encode_ht_block(integer_block(coded, job), magnitude_bitplanes, 0, distortion);
  if (params.ht) return ht::encode_ht_block(float_block(coded, job), magnitude_bitplanes, 0, distortion);
  if (params.lossless)
    return t1::encode_block(integer_block(coded, job), job.orientation, magnitude_bitplanes, params.block_style, stop,
                            distortion);
  return t1::encode_block(float_block(coded, job), job.orientation, magnitude_bitplanes, params.block_style, stop,
                          distortion);
}

CodedTile transform_tile(const SourceImage& image, SourceImage* consumable, const CodingPlan& plan,
                         const EncodeParams& params, int tile_index, dwt::DwtBackend& dwt,
                         dwt::DwtBackend& reversible_dwt, base::ThreadPool& pool, StageTimes& times) {
  const auto clock = Clock::now();
  CodedTile coded;
  coded.tile = build_tile(plan.grid, plan.sampling, plan.styles, tile_index);
  TilePlanes planes = load_tile_planes(image, consumable, plan, coded.tile, params.lossless, pool);
  times.level_shift += ms_since(clock);
  transform_planes(coded.tile, planes, params.lossless, dwt, reversible_dwt, times);
  coded.quantized = std::move(planes.integers);
  coded.coefficients = std::move(planes.floats);
  return coded;
}

// Where the step's phase aims, against the estimated crossing, in octaves: a tenth of an octave
// finer. The estimate ran 0.05-0.07 coarse on the 2048x2048 and 4096x4096 mosaics (7.01 and 6.88
// against the 6.94 and 6.83 real uniform encodes give), and the PSNR peaks 0.04-0.05 finer than the
// crossing itself (2048x2048 at 0.75 bpp: 34.645 dB at 6.90, 34.634 at 6.94, 34.589 at 7.00 and
// 34.526 at 7.10). The 16 photographs' mean gain over base_step's own phase at 0.25, 0.75 and
// 2 bpp: +0.047, +0.071 and +0.033 dB aiming at the estimate, +0.076, +0.085 and +0.056 dB a
// tenth finer, +0.067, +0.089 and +0.057 dB 0.05 finer.
constexpr double kHtPhaseOffset = -0.1;

std::optional<double> ht_aligned_base_step(CodedTile& coded, const CodingPlan& plan, const EncodeParams& params,
                                           const Tier1Target& target, base::ThreadPool& pool) {
  coded.jobs = block_jobs(coded.tile, plan, params.lossless);
  const std::optional<double> octaves = ht_uniform_step_octaves(coded, params, target, pool);
  if (!octaves) return std::nullopt;
  // The octave's phase, moved by at most half an octave either way.
  const double aim = *octaves + kHtPhaseOffset;
  double phase = aim - std::floor(aim);
  if (phase > 0.5) phase -= 1;
  const double step = params.base_step * std::exp2(phase);
  // The same phase an octave finer where the step would pass the sample range (EncodeParams allows
  // base steps up to 1).
  return step > 1 ? step / 2 : step;
}

void code_tile_blocks(CodedTile& coded, const CodingPlan& plan, const EncodeParams& params, base::ThreadPool& pool,
                      StageTimes& times, Tier1Target target, std::size_t progress_base, std::size_t progress_total) {
  const auto clock = Clock::now();
  const Tile& tile = coded.tile;
  const bool lossless = params.lossless;

  // Tier-1 on every code-block, in parallel, quantising lossy blocks as they are loaded. Blocks are
  // coded with Mb = 31, the most there can be; find_guard_bits then sets Mb and missing_msbs.
  coded.jobs = block_jobs(tile, plan, lossless);
  coded.blocks.resize(tile.code_blocks);
  coded.block_magnitude_bitplanes.assign(tile.code_blocks, 0);
  std::atomic<std::size_t> finished{0};
  auto run = [&](const std::vector<std::size_t>& which, t1::StopRule stop) {
    pool.parallel_for(which.size(), [&](std::size_t k) {
      const BlockJob& job = coded.jobs[which[k]];
      coded.blocks[job.block_index] = code_block(coded, job, params, 31, stop);
      if (params.progress) params.progress(progress_base + finished.fetch_add(1) + 1, progress_total);
    });
  };
  std::vector<std::size_t> all(coded.jobs.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (params.ht && !params.layers.empty()) {
    // HT under a target: cleanups from the planes near each block's predicted truncation (ht_rate.h).
    code_ht_candidates(coded, params, target, pool, [&] {
      if (params.progress) params.progress(progress_base + finished.fetch_add(1) + 1, progress_total);
    });
  } else if (target.kind == Tier1Target::Kind::None || target.value <= 0 || coded.jobs.size() < 64) {
    run(all, {});
  } else {
    // Code only what the budget keeps: a sample of the blocks, the threshold it predicts, then every
    // other block until its bit-planes fall well below that threshold. The encoder recodes in full
    // any block the final allocation cuts near where it stopped.
    const BlockSample sample = sample_blocks(coded.jobs, kSampleStride);
    coded.stop_threshold = code_sample(coded, sample, target, run) / kStopSafety;
    std::vector<bool> in_sample(all.size());
    for (std::size_t i : sample.blocks) in_sample[i] = true;
    std::vector<std::size_t> rest;
    for (std::size_t i : all)
      if (!in_sample[i]) rest.push_back(i);
    run(rest, t1::StopRule{coded.stop_threshold, 1});
  }
  find_guard_bits(tile, plan, coded);
  times.tier1 += ms_since(clock);
}

}  // namespace codec
