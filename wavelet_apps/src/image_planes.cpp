#include "wavelet_apps/image_planes.h"

#include <array>
#include <cmath>

#include "wavelet_apps/error.h"

namespace wavelet_apps {

namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

// T.800 equation G-5.
constexpr Matrix kIct = {{{0.299, 0.587, 0.114}, {-0.16875, -0.33126, 0.5}, {0.5, -0.41869, -0.08131}}};

// T.800's inverse (G-6) rounds its constants to 1.402, 0.34413, ...; the exact inverse of G-5 keeps
// edits with all factors 1 exact up to float rounding.
Matrix inverse_of(const Matrix& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Matrix inv{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      // Cofactor of (c, r), transposed.
      const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
      inv[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] =
          (m[static_cast<std::size_t>(r0)][static_cast<std::size_t>(c0)] *
               m[static_cast<std::size_t>(r1)][static_cast<std::size_t>(c1)] -
           m[static_cast<std::size_t>(r0)][static_cast<std::size_t>(c1)] *
               m[static_cast<std::size_t>(r1)][static_cast<std::size_t>(c0)]) /
          det;
    }
  return inv;
}

const Matrix& inverse_ict() {
  static const Matrix inv = inverse_of(kIct);
  return inv;
}

void multiply(const Matrix& m, float& a, float& b, float& c) {
  const double x = a, y = b, z = c;
  a = static_cast<float>(m[0][0] * x + m[0][1] * y + m[0][2] * z);
  b = static_cast<float>(m[1][0] * x + m[1][1] * y + m[1][2] * z);
  c = static_cast<float>(m[2][0] * x + m[2][1] * y + m[2][2] * z);
}

}  // namespace

void rgb_to_ycbcr(float& r_y, float& g_cb, float& b_cr) { multiply(kIct, r_y, g_cb, b_cr); }
void ycbcr_to_rgb(float& y_r, float& cb_g, float& cr_b) { multiply(inverse_ict(), y_r, cb_g, cr_b); }

ColourSpace parse_colour_space(std::string_view name) {
  if (name == "rgb") return ColourSpace::Rgb;
  if (name == "ycc") return ColourSpace::YCbCr;
  throw AppError("unknown colour space '" + std::string(name) + "' (expected rgb or ycc)");
}

std::vector<std::string> channel_names(int channels, ColourSpace space) {
  const bool ycc = space == ColourSpace::YCbCr;
  switch (channels) {
    case 1:
      return {"Y"};
    case 2:
      return {"Y", "A"};
    case 3:
      return ycc ? std::vector<std::string>{"Y", "Cb", "Cr"} : std::vector<std::string>{"R", "G", "B"};
    case 4:
      return ycc ? std::vector<std::string>{"Y", "Cb", "Cr", "A"} : std::vector<std::string>{"R", "G", "B", "A"};
    default:
      throw AppError("images of " + std::to_string(channels) + " channels are not supported (1 to 4)");
  }
}

Planes to_planes(const imageio::Image& image, ColourSpace space) {
  Planes p;
  p.width = image.width;
  p.height = image.height;
  p.names = channel_names(image.channels, space);
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  const std::size_t channels = static_cast<std::size_t>(image.channels);
  p.planes.assign(channels, std::vector<float>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < channels; ++c) p.planes[c][i] = image.pixels[i * channels + c];
  if (space == ColourSpace::YCbCr && channels >= 3)
    for (std::size_t i = 0; i < n; ++i) rgb_to_ycbcr(p.planes[0][i], p.planes[1][i], p.planes[2][i]);
  return p;
}

imageio::Image from_planes(const Planes& planes, ColourSpace space) {
  imageio::Image image;
  image.width = planes.width;
  image.height = planes.height;
  image.channels = static_cast<int>(planes.planes.size());
  image.bits_per_sample = 32;
  image.is_float = true;
  const std::size_t n = static_cast<std::size_t>(planes.width) * static_cast<std::size_t>(planes.height);
  const std::size_t channels = planes.planes.size();
  image.pixels.resize(n * channels);
  for (std::size_t i = 0; i < n; ++i) {
    float* px = &image.pixels[i * channels];
    for (std::size_t c = 0; c < channels; ++c) px[c] = planes.planes[c][i];
    if (space == ColourSpace::YCbCr && channels >= 3) ycbcr_to_rgb(px[0], px[1], px[2]);
  }
  return image;
}

float sample_range(const imageio::Image& image) {
  if (image.is_float) return 1.0f;
  return image.is_signed ? std::ldexp(1.0f, image.bits_per_sample - 1) - 1.0f
                         : std::ldexp(1.0f, image.bits_per_sample) - 1.0f;
}

imageio::Image to_format_of(const imageio::Image& values, const imageio::Image& like) {
  imageio::Image out = values;
  out.is_float = like.is_float;
  out.is_signed = like.is_signed;
  out.bits_per_sample = like.bits_per_sample;
  if (like.is_float) return out;
  const float hi = like.is_signed ? std::ldexp(1.0f, like.bits_per_sample - 1) - 1.0f
                                  : std::ldexp(1.0f, like.bits_per_sample) - 1.0f;
  const float lo = like.is_signed ? -std::ldexp(1.0f, like.bits_per_sample - 1) : 0.0f;
  for (float& v : out.pixels) {
    const float r = std::isfinite(v) ? std::round(v) : 0.0f;
    v = r < lo ? lo : (r > hi ? hi : r);
  }
  return out;
}

}  // namespace wavelet_apps
