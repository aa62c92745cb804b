#pragma once
#include <cstdint>
#include <vector>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// One component's line of the SIZ segment (T.800 Table A.11): Ssiz, XRsiz, YRsiz.
struct SizComponent {
  unsigned precision = 8;  // bit depth, 1..38; written as precision - 1
  bool is_signed = false;  // Ssiz bit 7
  unsigned xrsiz = 1;      // horizontal separation (subsampling) on the reference grid, 1..255
  unsigned yrsiz = 1;      // vertical separation, 1..255
};

// Image and tile size (T.800 A.5.1). The fields keep the standard's names so they can be checked
// against Figure B.1: the image area is [XOsiz, Xsiz) x [YOsiz, Ysiz) on the reference grid, and the
// tile grid starts at (XTOsiz, YTOsiz) with tiles XTsiz x YTsiz. Fields are 64-bit so a value that
// does not fit the 32-bit field is caught by validation rather than silently truncated.
struct Siz {
  std::uint16_t rsiz = 0;  // capabilities; 0 = Part 1 without restrictions
  std::uint64_t xsiz = 0;
  std::uint64_t ysiz = 0;
  std::uint64_t xosiz = 0;
  std::uint64_t yosiz = 0;
  std::uint64_t xtsiz = 0;
  std::uint64_t ytsiz = 0;
  std::uint64_t xtosiz = 0;
  std::uint64_t ytosiz = 0;
  std::vector<SizComponent> components;  // 1..16384 of them
};

// Throws CodestreamError unless every field is in range and the image, tile grid and origin
// satisfy the relations of T.800 A.5.1 (XOsiz < Xsiz, XTOsiz <= XOsiz, XTOsiz + XTsiz > XOsiz, the
// same for Y), and the tile count fits Isot (at most 65535 tiles).
void validate_siz(const Siz& siz);

// Number of tiles across and down (T.800 B-5): ceil((Xsiz - XTOsiz) / XTsiz). Expects a valid SIZ.
std::uint32_t num_tiles_x(const Siz& siz);
std::uint32_t num_tiles_y(const Siz& siz);
std::uint32_t num_tiles(const Siz& siz);

// Validates, then writes the SIZ marker segment: Lsiz = 38 + 3 * Csiz.
void write_siz(ByteWriter& out, const Siz& siz);

}  // namespace codec::cs
