#include "bench_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "imageio/read.h"
#include "testimages/patterns.h"

namespace bench {
namespace fs = std::filesystem;

std::string find_kodak_dir() {
  std::vector<fs::path> roots;
  if (const char* src = std::getenv("GPUJ2K_SOURCE_DIR")) roots.emplace_back(src);
#ifdef GPUJ2K_SOURCE_DIR_DEFAULT
  roots.emplace_back(GPUJ2K_SOURCE_DIR_DEFAULT);
#endif
  roots.emplace_back(fs::current_path());
  for (const auto& root : roots) {
    const fs::path dir = root / ".." / "shared" / "testimages" / "kodak";
    if (fs::exists(dir / "kodim01.png")) return fs::weakly_canonical(dir).string();
  }
  return "";
}

BenchPlane make_plane(int size, const std::string& kodak_dir) {
  BenchPlane plane;
  plane.size = size;
  plane.samples.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0.0f);
  if (kodak_dir.empty()) {
    const auto img = testimages::generate(testimages::Pattern::Mix, size, size, 1, 8);
    plane.samples = img.pixels;
    plane.source = "synthetic mix pattern (Kodak photographs not found)";
    return plane;
  }
  // Luma (ITU-R BT.601 weights) of kodim01..16, tiled left to right, top to bottom.
  std::vector<imageio::Image> photos;
  for (int i = 1; i <= 16; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "kodim%02d.png", i);
    const fs::path path = fs::path(kodak_dir) / name;
    if (!fs::exists(path)) continue;
    photos.push_back(imageio::read_image(path.string()));
    const auto& p = photos.back();
    if (p.width >= size && p.height >= size) break;  // one photograph is enough
  }
  int used = 0, x0 = 0, y0 = 0, row_height = 0;
  for (std::size_t k = 0; y0 < size; k = (k + 1) % photos.size()) {
    const auto& p = photos[k];
    const int w = std::min(p.width, size - x0), h = std::min(p.height, size - y0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float r = p.pixels[(static_cast<std::size_t>(y) * p.width + x) * p.channels];
        const float g = p.channels >= 3 ? p.pixels[(static_cast<std::size_t>(y) * p.width + x) * p.channels + 1] : r;
        const float b = p.channels >= 3 ? p.pixels[(static_cast<std::size_t>(y) * p.width + x) * p.channels + 2] : r;
        plane.samples[static_cast<std::size_t>(y0 + y) * size + (x0 + x)] = std::round(0.299f * r + 0.587f * g + 0.114f * b);
      }
    ++used;
    row_height = std::max(row_height, h);
    x0 += w;
    if (x0 >= size) {
      x0 = 0;
      y0 += row_height;
      row_height = 0;
    }
  }
  plane.source = used == 1 ? "crop of a Kodak photograph (luma)" : "mosaic of " + std::to_string(used) + " Kodak photograph tiles (luma)";
  return plane;
}

}  // namespace bench
