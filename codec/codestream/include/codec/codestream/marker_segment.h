#pragma once
#include <cstddef>
#include <cstdint>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// A marker segment is the marker, then Lxxx (u16), then its parameters; Lxxx counts itself and the
// parameters but not the marker (T.800 A.1.4). Writers begin a segment, append the parameters and
// end it, which fills in Lxxx. So no writer computes its length by hand and gets it wrong.
class MarkerSegment {
 public:
  // Writes the marker and a placeholder for Lxxx. `name` (e.g. "QCC") goes into error messages.
  MarkerSegment(ByteWriter& out, std::uint16_t marker, const char* name);

  // Patches Lxxx. Throws CodestreamError when the segment exceeds 65535 bytes, after removing the
  // segment from the output, so a failed write leaves no partial segment behind.
  void end();

 private:
  ByteWriter* out_;
  std::size_t start_;  // offset of the marker
  const char* name_;
};

}  // namespace codec::cs
