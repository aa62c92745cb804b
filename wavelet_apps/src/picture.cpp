#include "wavelet_apps/picture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace wavelet_apps {

namespace {

imageio::Image blank_rgb(int width, int height) {
  imageio::Image image;
  image.width = width;
  image.height = height;
  image.channels = 3;
  image.bits_per_sample = 8;
  image.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 255.0f);
  return image;
}

using Vec = std::array<double, 3>;
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

imageio::Image render_mesh(const SurfaceMesh& mesh, int width, int height, float yaw_degrees) {
  imageio::Image image = blank_rgb(width, height);
  if (mesh.positions.empty()) return image;
  const double yaw = yaw_degrees * std::numbers::pi / 180.0;
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  // View space: x right, y up, z toward the viewer.
  std::vector<Vec> view;
  view.reserve(mesh.positions.size());
  Vec lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
  for (const Point3& p : mesh.positions) {
    const Vec v{cy * p[0] + sy * p[2], double(p[1]), -sy * p[0] + cy * p[2]};
    for (int a = 0; a < 3; ++a) {
      lo[static_cast<std::size_t>(a)] = std::min(lo[static_cast<std::size_t>(a)], v[static_cast<std::size_t>(a)]);
      hi[static_cast<std::size_t>(a)] = std::max(hi[static_cast<std::size_t>(a)], v[static_cast<std::size_t>(a)]);
    }
    view.push_back(v);
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-12});
  const double scale = 0.9 * std::min(width, height) / extent;
  const double ox = 0.5 * width - scale * 0.5 * (lo[0] + hi[0]);
  const double oy = 0.5 * height + scale * 0.5 * (lo[1] + hi[1]);
  std::vector<Vec> screen;
  screen.reserve(view.size());
  for (const Vec& v : view) screen.push_back({ox + scale * v[0], oy - scale * v[1], v[2]});

  std::vector<double> depth(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                            -std::numeric_limits<double>::infinity());
  const Vec light = [] {
    const Vec l{-0.4, 0.5, 0.77};
    const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    return Vec{l[0] / n, l[1] / n, l[2] / n};
  }();
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const Vec& a = screen[mesh.indices[t]];
    const Vec& b = screen[mesh.indices[t + 1]];
    const Vec& c = screen[mesh.indices[t + 2]];
    // Shading from the view-space normal; both faces are lit, so open nets look right from behind.
    Vec n = cross(sub(view[mesh.indices[t + 1]], view[mesh.indices[t]]),
                  sub(view[mesh.indices[t + 2]], view[mesh.indices[t]]));
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len == 0) continue;
    const double lambert = std::abs(n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / len;
    const float shade = static_cast<float>(40.0 + 200.0 * lambert);
    const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a[0], b[0], c[0]}))));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({a[0], b[0], c[0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a[1], b[1], c[1]}))));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({a[1], b[1], c[1]}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        const double w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
        const double w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
        const double w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * a[2] + w1 * b[2] + w2 * c[2];
        double& d = depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
        if (z <= d) continue;
        d = z;
        image.at(x, y, 0) = std::round(shade * 0.95f);
        image.at(x, y, 1) = std::round(shade * 0.85f);
        image.at(x, y, 2) = std::round(shade * 0.75f);
      }
  }
  return image;
}

imageio::Image band_layout_picture(std::span<const dwt::BandOperation> ops, int columns, int rows, int size) {
  const double scale = static_cast<double>(size) / columns;
  const int width = size, height = std::max(1, static_cast<int>(std::lround(rows * scale)));
  imageio::Image image = blank_rgb(width, height);
  for (const dwt::BandOperation& op : ops) {
    float rgb[3] = {170, 170, 170};
    if (op.first_factor > 1.0f) rgb[0] = 220, rgb[1] = 60, rgb[2] = 50;
    if (op.first_factor < 1.0f) rgb[0] = 60, rgb[1] = 90, rgb[2] = 220;
    const int x0 = static_cast<int>(std::lround(op.rect.x * scale));
    const int y0 = static_cast<int>(std::lround(op.rect.y * scale));
    const int x1 = std::min(width, static_cast<int>(std::lround((op.rect.x + op.rect.width) * scale)));
    const int y1 = std::min(height, static_cast<int>(std::lround((op.rect.y + op.rect.height) * scale)));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const bool edge = x == x0 || y == y0 || x == x1 - 1 || y == y1 - 1;
        for (int c = 0; c < 3; ++c) image.at(x, y, c) = edge ? 255.0f : rgb[c];
      }
  }
  return image;
}

imageio::Image stack_pictures(const imageio::Image& top, const imageio::Image& bottom) {
  imageio::Image out = blank_rgb(std::max(top.width, bottom.width), top.height + bottom.height);
  auto paste = [&](const imageio::Image& src, int dy) {
    const int dx = (out.width - src.width) / 2;
    for (int y = 0; y < src.height; ++y)
      for (int x = 0; x < src.width; ++x)
        for (int c = 0; c < 3; ++c) out.at(x + dx, y + dy, c) = src.at(x, y, std::min(c, src.channels - 1));
  };
  paste(top, 0);
  paste(bottom, top.height);
  return out;
}

}  // namespace wavelet_apps
