#pragma once
#include <cstdint>

#include "codec/codestream/byte_writer.h"

namespace codec::cs {

// In-bitstream markers for the tier-2 writer (T.800 A.8), used when the COD's Scod enables them.

// Start of packet: SOP, Lsop = 4, Nsop = the packet's sequence number within the tile modulo 65536
// (the count restarts at 0 in each tile and wraps).
void write_sop(ByteWriter& out, std::uint64_t packet_index);

// End of packet header: the two-byte EPH marker, right after each packet header.
void write_eph(ByteWriter& out);

}  // namespace codec::cs
