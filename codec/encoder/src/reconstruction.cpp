#include "reconstruction.h"

#include <algorithm>
#include <cmath>

#include "quantization.h"
#include "codec/t1/reconstruction.h"

namespace codec {

double rebuilt_squared_error(const SourceImage& image, const CodingPlan& plan, const EncodeParams& params,
                             const std::vector<CodedTile>& tiles,
                             const std::vector<std::vector<std::vector<int>>>& passes, int layer, dwt::DwtBackend& dwt,
                             base::ThreadPool& pool) {
  double total = 0;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const CodedTile& coded = tiles[t];
    const Tile& tile = coded.tile;
    const std::size_t nc = tile.components.size();
    std::vector<std::vector<float>> planes(nc);
    for (std::size_t c = 0; c < nc; ++c)
      planes[c].assign(static_cast<std::size_t>(tile.components[c].rect.width()) *
                           static_cast<std::size_t>(tile.components[c].rect.height()),
                       0.0f);
    // Every block's dequantised reconstruction into its place in the Mallat layout, in parallel:
    // blocks cover disjoint rectangles.
    pool.parallel_for(coded.jobs.size(), [&](std::size_t k) {
      const BlockJob& job = coded.jobs[k];
      const auto bw = static_cast<std::size_t>(job.width), bh = static_cast<std::size_t>(job.height);
      const auto w = static_cast<std::size_t>(job.plane_width);
      const auto x0 = static_cast<std::size_t>(job.x0), y0 = static_cast<std::size_t>(job.y0);
      thread_local std::vector<std::int32_t> indices;
      thread_local std::vector<float> values;
      indices.resize(bw * bh);
      values.resize(indices.size());
      const FloatPlane& coefficients = coded.coefficients[job.component];
      for (std::size_t y = 0; y < bh; ++y)
        for (std::size_t x = 0; x < bw; ++x)
          indices[y * bw + x] = quantize(coefficients[(y0 + y) * w + x0 + x], job.inverse_step);
      int received = passes[t][job.block_index][static_cast<std::size_t>(layer)];
      if (!coded.ht_candidates.empty())  // HT: the chosen cleanup, as EBCOT's cleanup of the same plane
        received = ebcot_equivalent_passes(coded.ht_candidates[job.block_index],
                                           coded.blocks[job.block_index].bit_planes, received);
      t1::reconstruct(indices, job.width, job.height, job.orientation, coded.block_magnitude_bitplanes[job.block_index],
                      params.block_style, received, values);
      std::vector<float>& plane = planes[job.component];
      for (std::size_t y = 0; y < bh; ++y)
        for (std::size_t x = 0; x < bw; ++x) plane[(y0 + y) * w + x0 + x] = values[y * bw + x] * job.step;
    });
    for (std::size_t c = 0; c < nc; ++c) {
      const TileComponent& tc = tile.components[c];
      if (tc.rect.empty()) continue;
      dwt::DwtParams dp;
      dp.kernel = dwt::KernelId::Irreversible97;
      dp.levels = tc.levels;
      dp.origin = dwt::Origin{tc.rect.x0, tc.rect.y0};
      dp.levels_may_exceed_size = true;
      dwt.inverse(
          dwt::make_span(planes[c].data(), static_cast<int>(tc.rect.width()), static_cast<int>(tc.rect.height())), dp);
    }
    if (plan.ict) {  // T.800 G-10
      for (std::size_t i = 0; i < planes[0].size(); ++i) {
        const float y = planes[0][i], cb = planes[1][i], cr = planes[2][i];
        planes[0][i] = y + 1.402f * cr;
        planes[1][i] = y - 0.34413f * cb - 0.71414f * cr;
        planes[2][i] = y + 1.772f * cb;
      }
    }
    for (std::size_t c = 0; c < nc; ++c) {
      const TileComponent& tc = tile.components[c];
      const SourceComponent& src = image.components[c];
      const double shift = src.is_signed ? 0.0 : std::ldexp(1.0, src.precision - 1);
      const double lo = src.is_signed ? -std::ldexp(1.0, src.precision - 1) : 0.0;
      const double hi = src.is_signed ? std::ldexp(1.0, src.precision - 1) - 1 : std::ldexp(1.0, src.precision) - 1;
      const auto w = static_cast<std::size_t>(tc.rect.width());
      const std::size_t sx = static_cast<std::size_t>(tc.rect.x0 - plan.grid.image.x0);
      std::vector<std::int32_t> scratch(w);
      for (std::size_t y = 0; y < static_cast<std::size_t>(tc.rect.height()); ++y) {
        const std::size_t sy = static_cast<std::size_t>(tc.rect.y0 - plan.grid.image.y0) + y;
        const std::int32_t* original = source_row(image, c, sy, sx, w, scratch.data());
        for (std::size_t x = 0; x < w; ++x) {
          const double v = std::clamp(std::round(planes[c][y * w + x] + shift), lo, hi);
          const double d = v - original[x];
          total += d * d;
        }
      }
    }
  }
  return total;
}

}  // namespace codec
