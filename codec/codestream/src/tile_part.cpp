#include "codec/codestream/tile_part.h"

#include <string>

#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"

namespace codec::cs {
namespace {

constexpr std::size_t kPsotOffset = 6;  // SOT(2) Lsot(2) Isot(2), then Psot

}  // namespace

std::size_t write_sot(ByteWriter& out, const Sot& sot) {
  const std::string who =
      "SOT (tile " + std::to_string(sot.tile_index) + ", part " + std::to_string(sot.part_index) + ")";
  if (sot.tile_index > 65534) throw CodestreamError(who + ": tile index exceeds 65534");
  if (sot.part_index > 254) throw CodestreamError(who + ": tile-part index exceeds 254");
  if (sot.num_parts > 255)
    throw CodestreamError(who + ": " + std::to_string(sot.num_parts) + " tile-parts; at most 255");
  if (sot.num_parts != 0 && sot.part_index >= sot.num_parts)
    throw CodestreamError(who + ": tile-part index must be less than the tile's " + std::to_string(sot.num_parts) +
                          " tile-parts");

  const std::size_t start = out.size();
  MarkerSegment seg(out, marker::SOT, "SOT");
  out.u16(static_cast<std::uint16_t>(sot.tile_index));
  out.u32(0);  // Psot, patched by patch_psot
  out.u8(static_cast<std::uint8_t>(sot.part_index));
  out.u8(static_cast<std::uint8_t>(sot.num_parts));
  seg.end();
  return start;
}

void patch_psot(ByteWriter& out, std::size_t sot_offset) {
  if (sot_offset > out.size()) throw CodestreamError("Psot: SOT offset lies beyond the bytes written");
  const std::size_t length = out.size() - sot_offset;
  if (length > 0xFFFFFFFFu)
    throw CodestreamError("Psot: tile-part of " + std::to_string(length) + " bytes exceeds 2^32-1; split the tile");
  out.patch_u32(sot_offset + kPsotOffset, static_cast<std::uint32_t>(length));
}

}  // namespace codec::cs
