#include "wavelet_apps/image_apps.h"

#include <algorithm>
#include <cmath>

#include "wavelet_apps/error.h"

namespace wavelet_apps {

namespace {

imageio::Image float_copy(const imageio::Image& image) {
  imageio::Image f = image;
  f.is_float = true;
  f.is_signed = false;
  f.bits_per_sample = 32;
  return f;
}

// One channel of `image` as a plane with `channels` channels' worth of conversion applied.
float luma(const imageio::Image& image, std::size_t pixel) {
  const float* px = &image.pixels[pixel * static_cast<std::size_t>(image.channels)];
  return image.channels >= 3 ? 0.299f * px[0] + 0.587f * px[1] + 0.114f * px[2] : px[0];
}

// `image` converted to `channels` channels, same size.
imageio::Image with_channels(const imageio::Image& image, int channels, float opaque) {
  if (image.channels == channels) return image;
  imageio::Image out = image;
  out.channels = channels;
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  out.pixels.assign(n * static_cast<std::size_t>(channels), 0.0f);
  const bool source_colour = image.channels >= 3;
  for (std::size_t i = 0; i < n; ++i) {
    const float* src = &image.pixels[i * static_cast<std::size_t>(image.channels)];
    float* dst = &out.pixels[i * static_cast<std::size_t>(channels)];
    const int colour_channels = channels >= 3 ? 3 : 1;
    for (int c = 0; c < colour_channels; ++c)
      dst[c] = colour_channels == 1 ? luma(image, i) : (source_colour ? src[c] : src[0]);
    if (channels == 2 || channels == 4) {
      const bool source_alpha = image.channels == 2 || image.channels == 4;
      dst[channels - 1] = source_alpha ? src[image.channels - 1] : opaque;
    }
  }
  return out;
}

}  // namespace

Planes edit_planes(const imageio::Image& image, const EditSettings& settings, WaveletEngine& engine) {
  Planes planes = to_planes(image, settings.space);
  for (std::size_t c = 0; c < planes.planes.size(); ++c) {
    const auto ops =
        scale_operations(settings.bands, static_cast<int>(c), planes.width, planes.height, settings.params);
    engine.process(planes.span(c), {}, settings.params, ops);
  }
  return planes;
}

imageio::Image edit_image(const imageio::Image& image, const EditSettings& settings, WaveletEngine& engine) {
  return to_format_of(from_planes(edit_planes(image, settings, engine), settings.space), image);
}

Fit parse_fit(std::string_view name) {
  if (name == "resize") return Fit::Resize;
  if (name == "tile") return Fit::Tile;
  throw AppError("unknown fit '" + std::string(name) + "' (expected resize or tile)");
}

std::vector<RuleSpec> default_combine_rules(ColourSpace space, int channels) {
  const std::vector<std::string> names = channel_names(channels, space);
  const int levels = 32;  // the defaults name no level, so any count parses them
  if (space == ColourSpace::YCbCr || channels < 3) return {parse_rule_spec("Y:*:*=max", names, levels)};
  return {parse_rule_spec("R:*:*=max", names, levels), parse_rule_spec("G:*:*=max", names, levels),
          parse_rule_spec("B:*:*=max", names, levels)};
}

imageio::Image fit_detail(const imageio::Image& detail, const imageio::Image& base, Fit fit) {
  const float scale = sample_range(base) / sample_range(detail);
  const imageio::Image source = with_channels(float_copy(detail), base.channels, sample_range(detail));
  imageio::Image out = float_copy(base);
  const int C = base.channels, W = base.width, H = base.height;
  const int w = source.width, h = source.height;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < C; ++c) {
        float v = 0;
        if (fit == Fit::Tile) {
          v = source.at(x % w, y % h, c);
        } else {
          // Pixel centres map onto pixel centres; edges are clamped.
          const float sx =
              std::clamp((static_cast<float>(x) + 0.5f) * static_cast<float>(w) / static_cast<float>(W) - 0.5f, 0.0f,
                         static_cast<float>(w - 1));
          const float sy =
              std::clamp((static_cast<float>(y) + 0.5f) * static_cast<float>(h) / static_cast<float>(H) - 0.5f, 0.0f,
                         static_cast<float>(h - 1));
          const int x0 = static_cast<int>(sx), y0 = static_cast<int>(sy);
          const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
          const float fx = sx - static_cast<float>(x0), fy = sy - static_cast<float>(y0);
          const float top = source.at(x0, y0, c) * (1 - fx) + source.at(x1, y0, c) * fx;
          const float bottom = source.at(x0, y1, c) * (1 - fx) + source.at(x1, y1, c) * fx;
          v = top * (1 - fy) + bottom * fy;
        }
        out.at(x, y, c) = v * scale;
      }
  return out;
}

Planes combine_planes(const imageio::Image& base, const imageio::Image& detail, const CombineSettings& settings,
                      WaveletEngine& engine) {
  Planes first = to_planes(base, settings.space);
  const Planes second = to_planes(fit_detail(detail, base, settings.fit), settings.space);
  std::vector<RuleSpec> rules = default_combine_rules(settings.space, base.channels);
  rules.insert(rules.end(), settings.bands.begin(), settings.bands.end());
  const RuleSpec take_base{};
  for (std::size_t c = 0; c < first.planes.size(); ++c) {
    const auto ops = rule_operations(rules, static_cast<int>(c), first.width, first.height, settings.params, take_base);
    engine.process(first.span(c), second.span(c), settings.params, ops);
  }
  return first;
}

imageio::Image combine_images(const imageio::Image& base, const imageio::Image& detail, const CombineSettings& settings,
                              WaveletEngine& engine) {
  return to_format_of(from_planes(combine_planes(base, detail, settings, engine), settings.space), base);
}

Decoupled decouple_planes(const imageio::Image& image, const DecoupleSettings& settings, WaveletEngine& engine) {
  if (settings.params.levels < 1) throw AppError("decoupling needs at least one decomposition level");
  if (!(settings.guard > 0.0f)) throw AppError("the division guard must be positive");
  Decoupled out;
  out.decal = to_planes(image, ColourSpace::Rgb);
  out.illuminance = out.decal;
  const std::vector<ScaleSpec> only_lowest = {parse_scale_spec("*=0", out.decal.names, settings.params.levels),
                                              parse_scale_spec("LL=keep", out.decal.names, settings.params.levels)};
  const float range = sample_range(image);
  const float floor = settings.guard * range;
  for (std::size_t c = 0; c < out.decal.planes.size(); ++c) {
    std::vector<float>& light = out.illuminance.planes[c];
    const auto ops = scale_operations(only_lowest, static_cast<int>(c), image.width, image.height, settings.params);
    engine.process(out.illuminance.span(c), {}, settings.params, ops);
    std::vector<float>& decal = out.decal.planes[c];
    double original_sum = 0, ratio_sum = 0;
    for (std::size_t i = 0; i < decal.size(); ++i) {
      original_sum += decal[i];
      decal[i] /= std::max(light[i], floor);
      ratio_sum += decal[i];
    }
    const float rescale = ratio_sum > 0 ? static_cast<float>(original_sum / ratio_sum) : 0.0f;
    for (float& v : decal) v = std::clamp(v * rescale, 0.0f, range);
  }
  return out;
}

DecoupledImages decouple_image(const imageio::Image& image, const DecoupleSettings& settings, WaveletEngine& engine) {
  const Decoupled d = decouple_planes(image, settings, engine);
  return {to_format_of(from_planes(d.illuminance, ColourSpace::Rgb), image),
          to_format_of(from_planes(d.decal, ColourSpace::Rgb), image)};
}

}  // namespace wavelet_apps
