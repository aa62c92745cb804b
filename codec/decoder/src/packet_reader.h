#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "block_decoder.h"
#include "codec/structure/tile.h"
#include "codec/t1/block_style.h"

namespace codec::dec {

// Thrown when a packet runs past the end of the tile's data: the tile decodes with what came
// before it (a truncated stream is not a malformed one).
struct PacketTruncated : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Tag-tree decoder (T.800 B.10.2): the mirror of t2::TagTreeEncoder. Each node keeps the lower
// bound the bits read so far establish, and whether its value is known.
class TagTreeDecoder {
 public:
  TagTreeDecoder(int width, int height);
  // Reads what the encoder sent for "is leaf (x, y) below `threshold`?"; true if it is (its value
  // is then known).
  template <class BitSource>
  bool below(int x, int y, int threshold, BitSource& bits);
  // Reads the leaf's value completely; refuses values above `limit`.
  template <class BitSource>
  int value(int x, int y, int limit, BitSource& bits);

 private:
  struct Node {
    int low = 0;
    bool known = false;
  };
  template <class BitSource>
  bool walk(int x, int y, int threshold, BitSource& bits);
  std::vector<int> level_width_;
  std::vector<std::size_t> level_offset_;
  std::vector<Node> nodes_;
};

// Everything tier-2 learns about one code-block over the packets of its precinct.
struct BlockState {
  bool included = false;
  int lblock = 3;             // B.10.7.1
  int missing_msbs = 0;       // P, from the zero bit-plane tag tree
  int passes = 0;             // passes the headers announced (the segmentation counts them all)
  int kept_passes = 0;        // passes whose bytes arrived and are wanted: what tier-1 decodes
  bool segment_open = false;  // the last segment continues in a later packet
  std::vector<std::uint8_t> data;
  std::vector<Segment> segments;
};

// Per precinct and subband: the two tag trees of B.10.2.
struct PrecinctBandTrees {
  TagTreeDecoder inclusion, zero_bitplanes;
};

// Packet headers carried apart from the packet data (PPM / PPT, A.7.4-5): the tile's header bytes
// and the read position in them, advanced packet by packet.
struct PackedHeaders {
  std::span<const std::uint8_t> bytes;
  std::size_t pos = 0;
};

struct PacketContext {
  bool sop = false, eph = false;
  PackedHeaders* packed = nullptr;  // null: each header precedes its body in the packet data
  t1::BlockStyle style;
  bool ht = false;   // HT code-blocks (T.814): segments are cleanup passes and refinement pairs
  bool keep = true;  // false: parse only (a layer or resolution the caller does not want)
};

// Reads one packet (T.800 B.9, B.10: optional SOP, header with optional EPH, body) of `precinct`
// (with packed headers, the header and its EPH come from ctx.packed, SOP and body from `data`)
// at `layer` from data[pos...], updates the tag trees and block states, and returns the position
// after it. Throws PacketTruncated when the data ends inside the packet (the blocks then keep only
// what arrived whole), DecodeError for a malformed header. `file_offset` maps positions to the file.
std::size_t read_packet(std::span<const std::uint8_t> data, std::size_t pos, std::size_t file_offset,
                        const Precinct& precinct, int layer, std::vector<PrecinctBandTrees>& trees,
                        std::vector<BlockState>& blocks, const PacketContext& ctx);

}  // namespace codec::dec
