#pragma once
// The encoder option matrix of issue 3, in one place, so the lossless and lossy tests cover the same
// cases (j2k_lossless_test.cpp, j2k_lossy_matrix_test.cpp).
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

#include "codec/encoder/params.h"

namespace test_support {

// Image sizes down to a single sample and a single row or column.
inline constexpr std::pair<int, int> kThinAndTinySizes[] = {{1, 1}, {1, 37}, {37, 1}, {3, 5}, {127, 129}, {1000, 1}};

// Code-block shapes: every power of two from 4 to 1024 on one side, W * H <= 4096.
inline constexpr std::pair<int, int> kCodeBlockSizes[] = {{4, 4},  {8, 8},  {16, 16},  {32, 32},  {64, 64},
                                                          {4, 64}, {64, 4}, {128, 32}, {16, 256}, {1024, 4}};

// Tilings of a 45x38 image with image and tile-grid offsets, odd tile sizes included.
struct Tiling {
  std::int64_t ox, oy, tw, th, tx, ty;
  int levels;

  void apply(codec::EncodeParams& p) const {
    p.image_x0 = ox, p.image_y0 = oy, p.tile_width = tw, p.tile_height = th, p.tile_x0 = tx, p.tile_y0 = ty;
    p.levels = levels;
  }
  std::string name() const {
    std::ostringstream s;
    s << "origin " << ox << "," << oy << " tiles " << tw << "x" << th << " at " << tx << "," << ty;
    return s.str();
  }
  // The opj_compress options that encode the same tiling.
  std::string opj_options() const {
    std::ostringstream s;
    s << "-n " << levels + 1 << " -t " << tw << "," << th << " -d " << ox << "," << oy << " -T " << tx << "," << ty;
    return s.str();
  }
};
inline constexpr Tiling kTilings[] = {{0, 0, 32, 32, 0, 0, 3},
                                      {3, 1, 16, 16, 2, 0, 3},
                                      {5, 7, 17, 9, 4, 6, 3},
                                      {1, 1, 1, 64, 1, 0, 3},
                                      {9, 2, 7, 5, 9, 1, 2}};

// Progression order `order` (0..4) with an odd image origin, 8x8 code-blocks and, if asked,
// precincts shrinking with resolution, on 4 levels (for a 70x53 image).
inline void apply_order(codec::EncodeParams& p, int order, bool precincts) {
  p.order = static_cast<codec::Progression>(order);
  p.levels = 4;
  p.image_x0 = 3;
  p.image_y0 = 5;
  if (precincts) p.precincts = {{32, 32}, {16, 16}, {8, 8}};
  p.codeblock_width = 8;
  p.codeblock_height = 8;
}

}  // namespace test_support
