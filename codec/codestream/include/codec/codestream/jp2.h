#pragma once
#include <cstdint>
#include <vector>

#include "codec/codestream/siz.h"

namespace codec::cs {

struct Jp2Component {
  unsigned precision = 8;  // 1..38
  bool is_signed = false;
};

// What the JP2 header boxes describe (T.800 I.5.3). The colour space follows from the number of
// components, as the enumerated spaces allow: 1 greyscale, 2 greyscale + opacity, 3 sRGB,
// 4 sRGB + opacity; the opacity channel is always the last component.
struct Jp2Header {
  std::uint32_t width = 0;   // image area width, Xsiz - XOsiz
  std::uint32_t height = 0;  // image area height, Ysiz - YOsiz
  std::vector<Jp2Component> components;
};

// The header that describes the image of a codestream with this SIZ.
Jp2Header jp2_header_for(const Siz& siz);

// Wraps a codestream in a JP2 file (T.800 Annex I): signature box, file type box ('jp2 ' brand),
// JP2 header superbox (image header, bits per component when depths differ, enumerated colour
// specification, channel definition when there is opacity), then the contiguous codestream box.
// Throws CodestreamError for a header JP2 cannot express.
std::vector<std::uint8_t> wrap_jp2(const std::vector<std::uint8_t>& codestream, const Jp2Header& header);

// Wraps an HTJ2K codestream in a JPH file (T.814 | ISO/IEC 15444-15 Annex D): the JP2 file format
// with the brand 'jph ' in the file type box, which also lists 'jph ' as its one compatible brand,
// and the same signature, header and codestream boxes as wrap_jp2 (ihdr C = 7, an enumerated colr).
std::vector<std::uint8_t> wrap_jph(const std::vector<std::uint8_t>& codestream, const Jp2Header& header);

}  // namespace codec::cs
