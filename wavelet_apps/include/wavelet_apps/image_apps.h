// The image applications of thesis 4.7.2: subband editing, styling by combining two images
// (Figure 4.10) and texture-illuminance decoupling (Figure 4.11). Each is a pipeline of stages over
// float planes: split into channels (RGB or YCbCr), forward + band operation + inverse per channel
// on a WaveletEngine, join the channels.
#pragma once

#include <vector>

#include "dwt/params.h"
#include "imageio/image.h"
#include "wavelet_apps/band_spec.h"
#include "wavelet_apps/engine.h"
#include "wavelet_apps/image_planes.h"

namespace wavelet_apps {

// Edit: every band scaled by the factor of the last matching spec (default 1). The result has the
// input's sample format (rounded and clamped) unless the input is float.
struct EditSettings {
  dwt::DwtParams params;
  ColourSpace space = ColourSpace::Rgb;
  std::vector<ScaleSpec> bands;
};
imageio::Image edit_image(const imageio::Image& image, const EditSettings& settings, WaveletEngine& engine);
// The same, leaving the float result unrounded (what the tests compare).
Planes edit_planes(const imageio::Image& image, const EditSettings& settings, WaveletEngine& engine);

// Combine: the rules of the last matching spec per band. Before the user's specs come the thesis'
// defaults (Figure 4.10): for the first channel (Y in ycc, R in rgb, and then also G and B) every
// detail band takes the coefficient of larger magnitude ("max"), the lowest band is the base's (so
// the detail image's lowest band is removed), and in YCbCr the chroma channels are the base's.
enum class Fit { Resize, Tile };
Fit parse_fit(std::string_view name);  // "resize", "tile"
struct CombineSettings {
  dwt::DwtParams params;
  ColourSpace space = ColourSpace::YCbCr;
  Fit fit = Fit::Resize;
  std::vector<RuleSpec> bands;
};
std::vector<RuleSpec> default_combine_rules(ColourSpace space, int channels);
// The detail image brought to the base's size (bilinear resize, or tiled from its top-left corner)
// and channel count (grey repeated, colour to luma, alpha dropped or made opaque), in the base's
// sample range.
imageio::Image fit_detail(const imageio::Image& detail, const imageio::Image& base, Fit fit);
imageio::Image combine_images(const imageio::Image& base, const imageio::Image& detail, const CombineSettings& settings,
                              WaveletEngine& engine);
Planes combine_planes(const imageio::Image& base, const imageio::Image& detail, const CombineSettings& settings,
                      WaveletEngine& engine);

// Decouple: per channel, the illuminance is the inverse transform of the lowest band alone (every
// detail band zeroed); the decal is the original divided by the illuminance, the division guarded
// by max(illuminance, guard * range), rescaled so that its mean equals the original's mean, and
// clamped to [0, range] (range: the image format's largest value).
struct DecoupleSettings {
  dwt::DwtParams params;
  float guard = 1.0f / 64.0f;
};
struct Decoupled {
  Planes illuminance;  // float, unclamped
  Planes decal;        // float, clamped to [0, range]
};
Decoupled decouple_planes(const imageio::Image& image, const DecoupleSettings& settings, WaveletEngine& engine);
// The two images in the input's format.
struct DecoupledImages {
  imageio::Image illuminance;
  imageio::Image decal;
};
DecoupledImages decouple_image(const imageio::Image& image, const DecoupleSettings& settings, WaveletEngine& engine);

}  // namespace wavelet_apps
