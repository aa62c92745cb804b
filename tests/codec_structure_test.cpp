// The codec's geometry (T.800 Annex B): tiles on the reference grid, subbands per B-15 agreeing
// with the DWT's layout, precincts and code-blocks partitioning every subband exactly once.
#include <gtest/gtest.h>

#include <set>

#include "codec/structure/error.h"
#include "codec/structure/tile.h"

namespace {

using codec::Rect;

codec::ImageGrid grid(std::int64_t x0, std::int64_t y0, std::int64_t w, std::int64_t h, std::int64_t tw,
                      std::int64_t th, std::int64_t tx0, std::int64_t ty0) {
  return codec::ImageGrid{Rect{x0, y0, x0 + w, y0 + h}, tw, th, tx0, ty0};
}

TEST(CodecStructure, TilesCoverTheImageOnce) {
  const auto g = grid(3, 1, 17, 13, 5, 4, 2, 0);
  codec::validate(g);
  EXPECT_EQ(g.tiles_wide(), 4);  // ceil((20 - 2) / 5)
  EXPECT_EQ(g.tiles_high(), 4);  // ceil((14 - 0) / 4)
  std::int64_t area = 0;
  for (int t = 0; t < g.tile_count(); ++t) area += g.tile_rect(t).width() * g.tile_rect(t).height();
  EXPECT_EQ(area, 17 * 13);
  EXPECT_EQ(g.tile_rect(0), (Rect{3, 1, 7, 4}));
}

TEST(CodecStructure, RejectsImpossibleTilings) {
  EXPECT_THROW(codec::validate(grid(3, 1, 17, 13, 5, 4, 4, 0)), codec::EncodeError);   // XTOsiz > XOsiz
  EXPECT_THROW(codec::validate(grid(10, 0, 17, 13, 5, 4, 2, 0)), codec::EncodeError);  // first tile misses the image
  EXPECT_THROW(codec::validate(grid(0, 0, 0, 13, 5, 4, 0, 0)), codec::EncodeError);
  EXPECT_THROW(codec::validate(grid(0, 0, 70000, 70000, 1, 1, 0, 0)), codec::EncodeError);  // > 65535 tiles
}

TEST(CodecStructure, SubbandRectFollowsB15) {
  // A tile-component at x 3..20 with two levels: level 1 high-pass covers ceil((3-1)/2)=1 .. ceil((20-1)/2)=10.
  const Rect tc{3, 0, 20, 8};
  EXPECT_EQ(codec::subband_rect(tc, 1, codec::BandOrientation::HL), (Rect{1, 0, 10, 4}));
  EXPECT_EQ(codec::subband_rect(tc, 1, codec::BandOrientation::LH), (Rect{2, 0, 10, 4}));
  EXPECT_EQ(codec::subband_rect(tc, 2, codec::BandOrientation::LL), (Rect{1, 0, 5, 2}));
}

struct Case {
  codec::ImageGrid grid;
  codec::CodingStyle style;
};

TEST(CodecStructure, CodeBlocksPartitionEverySubbandExactlyOnce) {
  std::vector<Case> cases;
  cases.push_back({grid(0, 0, 64, 64, 64, 64, 0, 0), {}});
  cases.push_back({grid(3, 1, 17, 13, 5, 4, 2, 0), {3, 2, 2, {}}});
  cases.push_back({grid(7, 5, 300, 201, 128, 96, 3, 2), {5, 4, 3, {{3, 4}, {4, 4}, {5, 5}}}});
  cases.push_back({grid(0, 0, 1, 1, 1, 1, 0, 0), {5, 6, 6, {}}});
  cases.push_back({grid(1, 0, 1000, 1, 1000, 1, 0, 0), {4, 6, 2, {{1, 1}}}});
  for (const Case& c : cases)
    for (int t = 0; t < c.grid.tile_count(); ++t) {
      const codec::Tile tile = codec::build_tile(c.grid, {{1, 1}}, {c.style}, t);
      std::set<std::size_t> indices;
      for (const auto& tc : tile.components) {
        std::int64_t band_area = 0;
        for (const auto& res : tc.resolutions) {
          std::vector<std::int64_t> covered(res.bands.size(), 0);
          for (const auto& p : res.precincts)
            for (const auto& pb : p.bands) {
              const auto& band = res.bands[static_cast<std::size_t>(pb.band)];
              for (const auto& cb : pb.blocks) {
                EXPECT_FALSE(cb.rect.empty());
                EXPECT_EQ(cb.rect.intersect(band.rect), cb.rect);
                EXPECT_LE(cb.rect.width(), std::int64_t{1} << band.xcb);
                EXPECT_LE(cb.rect.height(), std::int64_t{1} << band.ycb);
                covered[static_cast<std::size_t>(pb.band)] += cb.rect.width() * cb.rect.height();
                EXPECT_TRUE(indices.insert(cb.index).second);
              }
            }
          for (std::size_t b = 0; b < res.bands.size(); ++b) {
            EXPECT_EQ(covered[b], res.bands[b].rect.width() * res.bands[b].rect.height())
                << "tile " << t << " r " << res.r;
            band_area += res.bands[b].rect.width() * res.bands[b].rect.height();
          }
        }
        EXPECT_EQ(band_area, tc.rect.width() * tc.rect.height());
      }
      EXPECT_EQ(indices.size(), tile.code_blocks);
    }
}

}  // namespace
