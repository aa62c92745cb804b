#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/decoder/decoder.h"

namespace codec::dec {

// A palette (pclr, T.800 I.5.3.4): `entries` rows of one value per column.
struct Jp2Palette {
  int entries = 0;                   // NE, 1..1024
  std::vector<int> precision;        // per column, 1..38 bits
  std::vector<bool> is_signed;       // per column
  std::vector<std::int64_t> values;  // entries x columns, row-major
  int columns() const { return static_cast<int>(precision.size()); }
};

// One output channel of a component mapping (cmap, I.5.3.5): codestream component `component`,
// either as it is (palette_column < 0) or through the palette's column `palette_column`.
struct Jp2ChannelSource {
  int component = 0;
  int palette_column = -1;
};

// A channel definition (cdef, I.5.3.6): channel `channel` is of type `type` (0 colour, 1 opacity,
// 2 premultiplied opacity, 65535 unspecified) and belongs to colour `association` (1.. in the
// colour space's order, 0 the whole image, 65535 none).
struct Jp2ChannelDefinition {
  int channel = 0, type = 0, association = 0;
};

// What the decoder takes from a JP2 file (T.800 Annex I): where the codestream lies and the
// header facts that change the output.
struct Jp2File {
  std::span<const std::uint8_t> codestream;
  std::size_t codestream_offset = 0;
  int colour_space = 0;  // colr method 1's EnumCS (16 sRGB, 17 greyscale, 18 sYCC), 0 if none
  // colr method 2 (restricted ICC): the profile's bytes; the samples are passed on as they are.
  std::vector<std::uint8_t> icc_profile;
  int ihdr_components = 0;                                // ihdr NC
  Jp2Palette palette;                                     // entries 0: no palette
  std::vector<Jp2ChannelSource> channel_sources;          // from cmap; empty: component i is channel i
  std::vector<Jp2ChannelDefinition> channel_definitions;  // from cdef; empty: none
  GridResolution capture_resolution, display_resolution;  // from res (resc, resd); 0: none
};

bool looks_like_jp2(std::span<const std::uint8_t> bytes);
// Walks the boxes, every length and count checked. Throws DecodeError for a malformed file.
Jp2File read_jp2(std::span<const std::uint8_t> bytes);

}  // namespace codec::dec
