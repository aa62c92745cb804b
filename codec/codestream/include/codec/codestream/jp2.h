#pragma once
#include <cstdint>
#include <vector>

#include "codec/codestream/siz.h"

namespace codec::cs {

struct Jp2Component {
  unsigned precision = 8;  // 1..38
  bool is_signed = false;
};

// A grid resolution for a JP2 resolution box (T.800 I.5.3.7): grid points per metre, vertically
// and horizontally; both 0 where there is none to write.
struct Jp2Resolution {
  double vertical = 0, horizontal = 0;
  bool given() const { return vertical > 0 && horizontal > 0; }
};

// A resolution as the box stores it: N / D * 10^E, each of N and D a 16-bit unsigned integer, E a
// signed byte (I.5.3.7.1).
struct Jp2ResolutionFraction {
  std::uint16_t numerator = 0, denominator = 1;
  std::int8_t exponent = 0;
};
// The fraction closest to `points_per_metre` (> 0, finite): the smallest exponent from 0 up that
// leaves at most 65535, then the best rational approximation of what remains (continued
// fractions); within 1 in 100,000 of the value.
// Throws CodestreamError for a value the box cannot hold (<= 0, not finite, or beyond 65535e127).
Jp2ResolutionFraction resolution_fraction(double points_per_metre);

// What the JP2 header boxes describe (T.800 I.5.3). The colour space follows from the number of
// components, as the enumerated spaces allow: 1 greyscale, 2 greyscale + opacity, 3 sRGB,
// 4 sRGB + opacity; the opacity channel is always the last component.
struct Jp2Header {
  std::uint32_t width = 0;   // image area width, Xsiz - XOsiz
  std::uint32_t height = 0;  // image area height, Ysiz - YOsiz
  std::vector<Jp2Component> components;
  // The resolution box (res) with its capture (resc) and display (resd) resolutions, where given.
  Jp2Resolution capture, display;
};

// The header that describes the image of a codestream with this SIZ.
Jp2Header jp2_header_for(const Siz& siz);

// Wraps a codestream in a JP2 file (T.800 Annex I): signature box, file type box ('jp2 ' brand),
// JP2 header superbox (image header, bits per component when depths differ, enumerated colour
// specification, channel definition when there is opacity, resolution when given), then the
// contiguous codestream box.
// Throws CodestreamError for a header JP2 cannot express.
std::vector<std::uint8_t> wrap_jp2(const std::vector<std::uint8_t>& codestream, const Jp2Header& header);

// Wraps an HTJ2K codestream in a JPH file (T.814 | ISO/IEC 15444-15 Annex D): the JP2 file format
// with the brand 'jph ' in the file type box, which also lists 'jph ' as its one compatible brand,
// and the same signature, header and codestream boxes as wrap_jp2 (ihdr C = 7, an enumerated colr).
std::vector<std::uint8_t> wrap_jph(const std::vector<std::uint8_t>& codestream, const Jp2Header& header);

}  // namespace codec::cs
