#pragma once
#include <cstddef>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// Start of tile-part (T.800 A.4.2).
struct Sot {
  unsigned tile_index = 0;  // Isot, 0..65534, tiles numbered in raster order
  unsigned part_index = 0;  // TPsot, 0..254, counts the tile's parts from 0 in codestream order
  unsigned num_parts = 1;   // TNsot, 1..255, or 0 when the count is not signalled in this part
};

// Validates, then writes the SOT segment (Lsot = 10) with Psot = 0 and returns the offset of the
// SOT marker, for patch_psot once the tile-part is complete.
std::size_t write_sot(ByteWriter& out, const Sot& sot);

// Sets Psot to the tile-part's length: from the first byte of its SOT marker to the end of the
// bytes written so far. Throws CodestreamError when that exceeds 2^32 - 1.
void patch_psot(ByteWriter& out, std::size_t sot_offset);

}  // namespace codec::cs
