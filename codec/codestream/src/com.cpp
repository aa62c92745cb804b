#include "codec/codestream/com.h"

#include <string>

#include "codec/codestream/error.h"
#include "codec/codestream/marker_segment.h"
#include "codec/codestream/markers.h"

namespace codec::cs {

Comment latin_comment(std::string_view text) {
  Comment c;
  c.registration = CommentRegistration::Latin;
  c.data.assign(text.begin(), text.end());
  return c;
}

void write_com(ByteWriter& out, const Comment& com) {
  if (com.registration != CommentRegistration::Binary && com.registration != CommentRegistration::Latin)
    throw CodestreamError("COM: registration " + std::to_string(static_cast<unsigned>(com.registration)) +
                          " is not 0 (binary) or 1 (Latin text)");
  if (com.data.size() > 65531)
    throw CodestreamError("COM: " + std::to_string(com.data.size()) + " bytes of comment; at most 65531 fit");
  MarkerSegment seg(out, marker::COM, "COM");
  out.u16(static_cast<std::uint16_t>(com.registration));
  out.bytes(com.data);
  seg.end();
}

}  // namespace codec::cs
