#include "codec/encoder/reconstruction.h"

#include <algorithm>
#include <cmath>

#include "codec/encoder/quantization.h"
#include "codec/t1/reconstruction.h"

namespace codec {
namespace {

t1::Orientation to_t1(BandOrientation o) { return static_cast<t1::Orientation>(static_cast<int>(o)); }

}  // namespace

double rebuilt_squared_error(const SourceImage& image, const CodingPlan& plan, const EncodeParams& params,
                             const std::vector<CodedTile>& tiles,
                             const std::vector<std::vector<std::vector<int>>>& passes, int layer,
                             dwt::DwtBackend& dwt) {
  double total = 0;
  std::vector<std::int32_t> indices;
  std::vector<float> values;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const CodedTile& coded = tiles[t];
    const Tile& tile = coded.tile;
    const std::size_t nc = tile.components.size();
    std::vector<std::vector<float>> planes(nc);
    for (std::size_t c = 0; c < nc; ++c) {
      const TileComponent& tc = tile.components[c];
      const auto w = static_cast<std::size_t>(tc.rect.width());
      planes[c].assign(w * static_cast<std::size_t>(tc.rect.height()), 0.0f);
      if (tc.rect.empty()) continue;
      const ComponentQuantization& q = plan.quantization[c];
      for (const Resolution& res : tc.resolutions) {
        const int first_band = res.r == 0 ? 0 : 1 + 3 * (res.r - 1);
        for (const Precinct& p : res.precincts)
          for (const PrecinctBand& pb : p.bands) {
            const Subband& band = res.bands[static_cast<std::size_t>(pb.band)];
            const auto step = static_cast<float>(q.steps[static_cast<std::size_t>(first_band + pb.band)]);
            for (const CodeBlock& cb : pb.blocks) {
              const int bw = static_cast<int>(cb.rect.width()), bh = static_cast<int>(cb.rect.height());
              const std::size_t x0 = static_cast<std::size_t>(band.layout.x + (cb.rect.x0 - band.rect.x0));
              const std::size_t y0 = static_cast<std::size_t>(band.layout.y + (cb.rect.y0 - band.rect.y0));
              indices.resize(static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh));
              values.resize(indices.size());
              const auto inverse_step = static_cast<float>(1.0 / q.steps[static_cast<std::size_t>(first_band + pb.band)]);
              for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x)
                  indices[static_cast<std::size_t>(y) * static_cast<std::size_t>(bw) + static_cast<std::size_t>(x)] =
                      quantize(coded.coefficients[c][(y0 + static_cast<std::size_t>(y)) * w + x0 + static_cast<std::size_t>(x)],
                               inverse_step);
              t1::reconstruct(indices, bw, bh, to_t1(band.orientation), coded.block_magnitude_bitplanes[cb.index],
                              params.block_style, passes[t][cb.index][static_cast<std::size_t>(layer)], values);
              for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x)
                  planes[c][(y0 + static_cast<std::size_t>(y)) * w + x0 + static_cast<std::size_t>(x)] =
                      values[static_cast<std::size_t>(y) * static_cast<std::size_t>(bw) + static_cast<std::size_t>(x)] * step;
            }
          }
      }
      dwt::DwtParams dp;
      dp.kernel = dwt::KernelId::Irreversible97;
      dp.levels = tc.levels;
      dp.origin = dwt::Origin{tc.rect.x0, tc.rect.y0};
      dp.levels_may_exceed_size = true;
      dwt.inverse(dwt::make_span(planes[c].data(), static_cast<int>(tc.rect.width()), static_cast<int>(tc.rect.height())), dp);
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
      for (std::size_t y = 0; y < static_cast<std::size_t>(tc.rect.height()); ++y)
        for (std::size_t x = 0; x < w; ++x) {
          const double v = std::clamp(std::round(planes[c][y * w + x] + shift), lo, hi);
          const std::size_t sy = static_cast<std::size_t>(tc.rect.y0 - plan.grid.image.y0) + y;
          const std::size_t sx = static_cast<std::size_t>(tc.rect.x0 - plan.grid.image.x0) + x;
          const double d = v - src.samples[sy * static_cast<std::size_t>(image.width) + sx];
          total += d * d;
        }
    }
  }
  return total;
}

}  // namespace codec
