#include "codec/codestream/marker_segment.h"

#include <string>

#include "codec/codestream/error.h"

namespace codec::cs {

MarkerSegment::MarkerSegment(ByteWriter& out, std::uint16_t marker, const char* name)
    : out_(&out), start_(out.size()), name_(name) {
  out.u16(marker);
  out.u16(0);
}

void MarkerSegment::end() {
  const std::size_t length = out_->size() - start_ - 2;  // Lxxx excludes the marker itself
  if (length > 0xFFFF) {
    out_->truncate(start_);
    throw CodestreamError(std::string(name_) + " marker segment would be " + std::to_string(length) +
                          " bytes long; its length field holds at most 65535");
  }
  out_->patch_u16(start_ + 2, static_cast<std::uint16_t>(length));
}

}  // namespace codec::cs
