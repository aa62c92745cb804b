#include "codec/codestream/delimiters.h"

#include "codec/codestream/markers.h"

namespace codec::cs {

void write_soc(ByteWriter& out) { out.u16(marker::SOC); }
void write_sod(ByteWriter& out) { out.u16(marker::SOD); }
void write_eoc(ByteWriter& out) { out.u16(marker::EOC); }

}  // namespace codec::cs
