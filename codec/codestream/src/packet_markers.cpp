#include "codec/codestream/packet_markers.h"

#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"

namespace codec::cs {

void write_sop(ByteWriter& out, std::uint64_t packet_index) {
  MarkerSegment seg(out, marker::SOP, "SOP");
  out.u16(static_cast<std::uint16_t>(packet_index & 0xFFFF));
  seg.end();
}

void write_eph(ByteWriter& out) { out.u16(marker::EPH); }

}  // namespace codec::cs
