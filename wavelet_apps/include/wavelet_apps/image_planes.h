// Images as the float planes the wavelet engine transforms, in RGB or YCbCr (the irreversible
// component transform, ICT, of T.800 Annex G.2), and back.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "dwt/plane.h"
#include "imageio/image.h"

namespace wavelet_apps {

enum class ColourSpace { Rgb, YCbCr };
ColourSpace parse_colour_space(std::string_view name);  // "rgb", "ycc"; AppError otherwise

// One float plane per channel, row-major.
struct Planes {
  int width = 0;
  int height = 0;
  std::vector<std::string> names;  // channel names for band specs: R, G, B (or Y, Cb, Cr), A; grey: Y
  std::vector<std::vector<float>> planes;

  dwt::PlaneSpan<float> span(std::size_t c) { return dwt::make_span(planes[c].data(), width, height); }
  dwt::PlaneSpan<const float> span(std::size_t c) const { return {planes[c].data(), width, height, width}; }
};

// The channel names an image of `channels` channels gets in `space` (1 to 4 channels; AppError else).
std::vector<std::string> channel_names(int channels, ColourSpace space);

// Splits the image into planes; with YCbCr the first three channels go through the ICT (alpha stays).
Planes to_planes(const imageio::Image& image, ColourSpace space);
// The inverse of to_planes: a float image (bits_per_sample 32) of the planes' channels.
imageio::Image from_planes(const Planes& planes, ColourSpace space);

// A float image rounded (half away from zero) and clamped into `like`'s integer range, with `like`'s
// precision and signedness; a float `like` gives the float image unchanged.
imageio::Image to_format_of(const imageio::Image& values, const imageio::Image& like);

// The largest sample value of `image`'s format: 2^bits - 1 for integers, 1 for float images.
float sample_range(const imageio::Image& image);

// ICT on one pixel, in place (T.800 equation G-5); the inverse is the exact inverse of that matrix,
// so a round trip is exact up to float rounding.
void rgb_to_ycbcr(float& r_y, float& g_cb, float& b_cr);
void ycbcr_to_rgb(float& y_r, float& cb_g, float& cr_b);

}  // namespace wavelet_apps
