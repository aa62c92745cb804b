#include "jp2_colour.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace codec::dec {

namespace {

// cmap + pclr (I.5.3.4-5): each channel is a component as it is, or a palette column indexed by a
// component's samples (clamped to the palette, as a viewer must do with out-of-range indices).
std::vector<DecodedComponent> map_channels(const Jp2File& jp2, const std::vector<DecodedComponent>& components) {
  const Jp2Palette& palette = jp2.palette;
  std::vector<DecodedComponent> channels;
  for (const Jp2ChannelSource& source : jp2.channel_sources) {
    if (source.component >= static_cast<int>(components.size()))
      throw DecodeError("JP2 cmap names component " + std::to_string(source.component) + " of " +
                        std::to_string(components.size()));
    const DecodedComponent& from = components[static_cast<std::size_t>(source.component)];
    if (source.palette_column < 0) {
      channels.push_back(from);
      continue;
    }
    if (palette.entries == 0) throw DecodeError("JP2 cmap maps through a palette, but there is no pclr box");
    if (from.precision > 31)
      throw DecodeError("JP2 palette indices of " + std::to_string(from.precision) + " bits (at most 31 supported)");
    const auto column = static_cast<std::size_t>(source.palette_column);
    if (palette.precision[column] > 31)
      throw DecodeError("JP2 palette column of " + std::to_string(palette.precision[column]) +
                        " bits (at most 31 supported)");
    DecodedComponent out = from;
    out.precision = palette.precision[column];
    out.is_signed = palette.is_signed[column];
    for (std::int32_t& v : out.samples) {
      const auto index = static_cast<std::size_t>(std::clamp(v, 0, palette.entries - 1));
      v = static_cast<std::int32_t>(palette.values[index * static_cast<std::size_t>(palette.columns()) + column]);
    }
    channels.push_back(std::move(out));
  }
  return channels;
}

// cdef (I.5.3.6): colour channels by association (1 = the colour space's first colour), then
// the others (opacity, unspecified) in channel order.
std::vector<DecodedComponent> order_channels(const std::vector<Jp2ChannelDefinition>& defs,
                                             std::vector<DecodedComponent> channels) {
  std::vector<bool> defined(channels.size(), false);
  for (const Jp2ChannelDefinition& d : defs) {
    if (d.channel >= static_cast<int>(channels.size()) || defined[static_cast<std::size_t>(d.channel)])
      throw DecodeError("JP2 cdef names channel " + std::to_string(d.channel) + " of " +
                        std::to_string(channels.size()) +
                        (d.channel < static_cast<int>(channels.size()) ? " twice" : ""));
    defined[static_cast<std::size_t>(d.channel)] = true;
  }
  std::vector<Jp2ChannelDefinition> colours;
  for (const Jp2ChannelDefinition& d : defs)
    if (d.type == 0 && d.association >= 1 && d.association < 65535) colours.push_back(d);
  std::stable_sort(colours.begin(), colours.end(),
                   [](const auto& a, const auto& b) { return a.association < b.association; });
  std::vector<bool> placed(channels.size(), false);
  std::vector<DecodedComponent> out;
  for (const Jp2ChannelDefinition& d : colours) {
    out.push_back(std::move(channels[static_cast<std::size_t>(d.channel)]));
    placed[static_cast<std::size_t>(d.channel)] = true;
  }
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!placed[c]) out.push_back(std::move(channels[c]));
  return out;
}

// The sample of `chroma` that covers the luma sample (x, y) of `luma` on the reference grid
// (replication: the chroma sample whose area contains it, B-12).
std::int32_t covering_sample(const DecodedComponent& chroma, const DecodedComponent& luma, int x, int y) {
  const std::int64_t gx = (static_cast<std::int64_t>(luma.x0) + x) * luma.dx,
                     gy = (static_cast<std::int64_t>(luma.y0) + y) * luma.dy;
  const std::int64_t cx = std::clamp<std::int64_t>(gx / chroma.dx - chroma.x0, 0, chroma.width - 1);
  const std::int64_t cy = std::clamp<std::int64_t>(gy / chroma.dy - chroma.y0, 0, chroma.height - 1);
  return chroma
      .samples[static_cast<std::size_t>(cy) * static_cast<std::size_t>(chroma.width) + static_cast<std::size_t>(cx)];
}

// sYCC to sRGB (IEC 61966-2-1 Amendment 1: the inverse of its R'G'B' to Y'CbCr matrix, chroma
// centred on 2^(precision-1)), rounded and clamped to the luma's unsigned range.
void sycc_to_srgb(std::vector<DecodedComponent>& channels) {
  const DecodedComponent& y = channels[0];
  if (y.is_signed || y.precision > 16)
    throw DecodeError("sYCC with signed or deeper than 16-bit luma is not supported");
  const double centre = std::ldexp(1.0, channels[1].precision - 1);
  const double top = std::ldexp(1.0, y.precision) - 1;
  DecodedComponent r = y, g = y, b = y;
  for (int row = 0; row < y.height; ++row)
    for (int col = 0; col < y.width; ++col) {
      const std::size_t i =
          static_cast<std::size_t>(row) * static_cast<std::size_t>(y.width) + static_cast<std::size_t>(col);
      const double luma = y.samples[i];
      const double cb = covering_sample(channels[1], y, col, row) - centre;
      const double cr = covering_sample(channels[2], y, col, row) - centre;
      auto out = [&](double v) { return static_cast<std::int32_t>(std::clamp(std::nearbyint(v), 0.0, top)); };
      r.samples[i] = out(luma + 1.402 * cr);
      g.samples[i] = out(luma - 0.344136 * cb - 0.714136 * cr);
      b.samples[i] = out(luma + 1.772 * cb);
    }
  channels[0] = std::move(r);
  channels[1] = std::move(g);
  channels[2] = std::move(b);
}

}  // namespace

void apply_jp2_channels(const Jp2File& jp2, bool to_srgb, DecodedImage& image) {
  if (!jp2.channel_sources.empty()) image.components = map_channels(jp2, image.components);
  if (!jp2.channel_definitions.empty())
    image.components = order_channels(jp2.channel_definitions, std::move(image.components));
  image.jp2_colour_space = jp2.colour_space;
  if (to_srgb && jp2.colour_space == 18 && image.components.size() >= 3) {
    sycc_to_srgb(image.components);
    image.jp2_colour_space = 16;
  }
}

}  // namespace codec::dec
