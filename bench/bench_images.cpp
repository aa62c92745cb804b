#include "bench_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

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
    if (fs::exists(dir / "kodim01.png") || fs::exists(dir / "kodim01.ppm")) return fs::weakly_canonical(dir).string();
  }
  return "";
}

imageio::Image kodak_mosaic(int size, const std::string& kodak_dir, int& used) {
  std::vector<imageio::Image> photos;
  for (int i = 1; i <= 16; ++i) {
    // PPM conversions serve where OpenImageIO, which reads the PNGs, is absent (a codec-alone build,
    // a machine the benchmarks are carried to).
    fs::path path;
    for (const char* ext : {"png", "ppm"}) {
      char name[32];
      std::snprintf(name, sizeof name, "kodim%02d.%s", i, ext);
      if (fs::exists(fs::path(kodak_dir) / name)) {
        path = fs::path(kodak_dir) / name;
        break;
      }
    }
    if (path.empty()) continue;
    photos.push_back(imageio::read_image(path.string()));
    const auto& p = photos.back();
    if (p.channels != 3 || p.is_float || p.bits_per_sample != 8)
      throw std::runtime_error(path.string() + ": expected an 8-bit RGB photograph");
    if (p.width >= size && p.height >= size) break;  // one photograph is enough
  }
  if (photos.empty()) throw std::runtime_error(kodak_dir + ": no kodimNN.png (or .ppm) photographs there");
  imageio::Image out;
  out.width = out.height = size;
  out.channels = 3;
  out.bits_per_sample = 8;
  out.pixels.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 3, 0.0f);
  used = 0;
  int x0 = 0, y0 = 0, row_height = 0;
  for (std::size_t k = 0; y0 < size; k = (k + 1) % photos.size()) {
    const auto& p = photos[k];
    const int w = std::min(p.width, size - x0), h = std::min(p.height, size - y0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) out.at(x0 + x, y0 + y, c) = p.at(x, y, c);
    ++used;
    row_height = std::max(row_height, h);
    x0 += w;
    if (x0 >= size) {
      x0 = 0;
      y0 += row_height;
      row_height = 0;
    }
  }
  return out;
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
  // Luma (ITU-R BT.601 weights) of the RGB mosaic.
  int used = 0;
  const imageio::Image rgb = kodak_mosaic(size, kodak_dir, used);
  for (std::size_t i = 0; i < plane.samples.size(); ++i)
    plane.samples[i] =
        std::round(0.299f * rgb.pixels[3 * i] + 0.587f * rgb.pixels[3 * i + 1] + 0.114f * rgb.pixels[3 * i + 2]);
  plane.source = used == 1 ? "crop of a Kodak photograph (luma)"
                           : "mosaic of " + std::to_string(used) + " Kodak photograph tiles (luma)";
  return plane;
}

}  // namespace bench
