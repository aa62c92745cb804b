#pragma once
#include <string>
#include <vector>

#include "imageio/image.h"

namespace bench {

// A square greyscale plane for benchmarking, with a line saying where its content came from.
struct BenchPlane {
  int size = 0;
  std::vector<float> samples;  // 8-bit luma values, row-major
  std::string source;
};

// Natural content where the Kodak photographs are present (a crop of one photograph, or a mosaic of
// several for sizes beyond 768), the project's synthetic "mix" pattern otherwise.
BenchPlane make_plane(int size, const std::string& kodak_dir);

// A square 8-bit RGB image: a crop of one Kodak photograph, or for sizes no single photograph
// covers, kodim01..16 tiled left to right, top to bottom. `used` counts the photographs placed.
imageio::Image kodak_mosaic(int size, const std::string& kodak_dir, int& used);

// The Kodak folder relative to the project root (../shared/testimages/kodak), or "" if absent.
std::string find_kodak_dir();

}  // namespace bench
