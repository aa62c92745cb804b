#include "codec/structure/tile.h"

#include <string>
#include <tuple>

#include "codec/structure/error.h"

namespace codec {
namespace {

// ceil(a / 2^e) for any sign of a (B-15 subtracts before dividing).
std::int64_t ceil_shift_signed(std::int64_t a, int e) {
  const std::int64_t d = std::int64_t{1} << e;
  return a >= 0 ? (a + d - 1) / d : -((-a) / d);
}

Subband make_subband(const TileComponent& tc, const std::vector<dwt::LevelGeometry>& levels, int nb,
                     BandOrientation o) {
  Subband b;
  b.orientation = o;
  b.level = nb;
  b.rect = subband_rect(tc.rect, nb, o);
  if (nb == 0)
    b.layout = dwt::LayoutRect{0, 0, static_cast<int>(tc.rect.width()), static_cast<int>(tc.rect.height())};
  else
    b.layout = dwt::band_rect(levels, nb, o);
  // The DWT's Mallat layout and B-15 are two statements of the same split; they must agree.
  if (b.layout.width != b.rect.width() || b.layout.height != b.rect.height())
    throw EncodeError("internal: subband geometry disagrees with the DWT layout");
  return b;
}

// The code-blocks of precinct-band region `region` (subband coordinates), anchored at 0 (B.7).
PrecinctBand partition(const Subband& band, int band_index, const Rect& region, std::size_t& next_index) {
  PrecinctBand pb;
  pb.band = band_index;
  if (region.empty()) return pb;
  const std::int64_t cx0 = floor_shift(region.x0, band.xcb), cy0 = floor_shift(region.y0, band.ycb);
  pb.cols = static_cast<int>(ceil_shift(region.x1, band.xcb) - cx0);
  pb.rows = static_cast<int>(ceil_shift(region.y1, band.ycb) - cy0);
  for (int j = 0; j < pb.rows; ++j)
    for (int i = 0; i < pb.cols; ++i) {
      const Rect cell{(cx0 + i) << band.xcb, (cy0 + j) << band.ycb, (cx0 + i + 1) << band.xcb,
                      (cy0 + j + 1) << band.ycb};
      pb.blocks.push_back(CodeBlock{cell.intersect(region), next_index++});
    }
  return pb;
}

}  // namespace

std::pair<int, int> CodingStyle::precinct(int r) const {
  if (precincts.empty()) return {15, 15};
  return precincts[static_cast<std::size_t>(std::min<int>(r, static_cast<int>(precincts.size()) - 1))];
}

Rect subband_rect(const Rect& tc, int nb, BandOrientation o) {
  if (nb == 0) return tc;
  const int xob = (o == BandOrientation::HL || o == BandOrientation::HH) ? 1 : 0;
  const int yob = (o == BandOrientation::LH || o == BandOrientation::HH) ? 1 : 0;
  const std::int64_t hx = xob ? (std::int64_t{1} << (nb - 1)) : 0, hy = yob ? (std::int64_t{1} << (nb - 1)) : 0;
  return Rect{ceil_shift_signed(tc.x0 - hx, nb), ceil_shift_signed(tc.y0 - hy, nb), ceil_shift_signed(tc.x1 - hx, nb),
              ceil_shift_signed(tc.y1 - hy, nb)};
}

Tile build_tile(const ImageGrid& grid, const std::vector<ComponentSampling>& sampling,
                const std::vector<CodingStyle>& styles, int tile_index) {
  Tile tile;
  tile.index = tile_index;
  tile.rect = grid.tile_rect(tile_index);
  for (std::size_t c = 0; c < sampling.size(); ++c) {
    const CodingStyle& style = styles[c];
    TileComponent tc;
    tc.component = static_cast<int>(c);
    tc.rect = tile_component_rect(tile.rect, sampling[c].dx, sampling[c].dy);
    tc.levels = style.levels;
    const auto levels = dwt::decomposition(static_cast<int>(tc.rect.width()), static_cast<int>(tc.rect.height()),
                                           dwt::Origin{tc.rect.x0, tc.rect.y0}, tc.levels);
    for (int r = 0; r <= tc.levels; ++r) {
      Resolution res;
      res.r = r;
      const int shift = tc.levels - r;
      res.rect = Rect{ceil_shift(tc.rect.x0, shift), ceil_shift(tc.rect.y0, shift), ceil_shift(tc.rect.x1, shift),
                      ceil_shift(tc.rect.y1, shift)};
      std::tie(res.ppx, res.ppy) = style.precinct(r);
      if (r > 0 && (res.ppx == 0 || res.ppy == 0))
        throw EncodeError("precinct size exponents must be at least 1 above resolution 0 (T.800 A.6.1)");
      // Precincts in band coordinates are half as large above resolution 0 (B.6), and code-blocks
      // never straddle a precinct (B.7).
      const int band_ppx = r == 0 ? res.ppx : res.ppx - 1, band_ppy = r == 0 ? res.ppy : res.ppy - 1;
      if (r == 0) {
        res.bands.push_back(make_subband(tc, levels, tc.levels, BandOrientation::LL));
      } else {
        for (BandOrientation o : {BandOrientation::HL, BandOrientation::LH, BandOrientation::HH})
          res.bands.push_back(make_subband(tc, levels, tc.levels - r + 1, o));
      }
      for (Subband& b : res.bands) {
        b.xcb = std::min(style.xcb, band_ppx);
        b.ycb = std::min(style.ycb, band_ppy);
      }
      if (!res.rect.empty()) {
        res.precincts_wide = static_cast<int>(ceil_shift(res.rect.x1, res.ppx) - floor_shift(res.rect.x0, res.ppx));
        res.precincts_high = static_cast<int>(ceil_shift(res.rect.y1, res.ppy) - floor_shift(res.rect.y0, res.ppy));
      }
      const std::int64_t px0 = floor_shift(res.rect.x0, res.ppx), py0 = floor_shift(res.rect.y0, res.ppy);
      for (int j = 0; j < res.precincts_high; ++j)
        for (int i = 0; i < res.precincts_wide; ++i) {
          Precinct p;
          p.rect = Rect{(px0 + i) << res.ppx, (py0 + j) << res.ppy, (px0 + i + 1) << res.ppx, (py0 + j + 1) << res.ppy}
                       .intersect(res.rect);
          for (std::size_t bi = 0; bi < res.bands.size(); ++bi) {
            const Subband& band = res.bands[bi];
            const Rect region =
                Rect{(px0 + i) << band_ppx, (py0 + j) << band_ppy, (px0 + i + 1) << band_ppx, (py0 + j + 1) << band_ppy}
                    .intersect(band.rect);
            p.bands.push_back(partition(band, static_cast<int>(bi), region, tile.code_blocks));
          }
          res.precincts.push_back(std::move(p));
        }
      tc.resolutions.push_back(std::move(res));
    }
    tile.components.push_back(std::move(tc));
  }
  return tile;
}

}  // namespace codec
