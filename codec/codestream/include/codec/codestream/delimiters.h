#pragma once
#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// The bare delimiting markers (T.800 A.4), which carry no length or parameters.
void write_soc(ByteWriter& out);  // first two bytes of every codestream
void write_sod(ByteWriter& out);  // ends a tile-part header; the packet data follows
void write_eoc(ByteWriter& out);  // last two bytes of every codestream

}  // namespace codec::cs
