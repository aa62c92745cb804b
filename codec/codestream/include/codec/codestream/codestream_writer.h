#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "codec/codestream/main_header.h"

namespace codec::cs {

// Assembles a codestream: the main header, then tile-parts (SOT, SOD, packet data; Psot filled in),
// then EOC. Tile-part headers carry no marker segments besides SOT: every tile uses the main
// header's COD/COC/QCD/QCC.
//
// It enforces the ordering rules of T.800 A.4.2 that a decoder relies on: tile-parts of one tile
// come in order of TPsot (starting at 0), a nonzero TNsot agrees across the tile's parts and
// matches how many were written, and, at finish(), every tile has at least one tile-part.
class CodestreamWriter {
 public:
  // Validates the header and writes it; throws CodestreamError.
  explicit CodestreamWriter(const MainHeader& header);

  // Appends one tile-part. `num_parts` is TNsot: the tile's total number of tile-parts, or 0 for
  // "not signalled here". `body` is the tile-part's packet data, written after SOD.
  void add_tile_part(unsigned tile_index, unsigned part_index, unsigned num_parts, std::span<const std::uint8_t> body);

  // Appends EOC and hands over the codestream. The writer is empty afterwards.
  std::vector<std::uint8_t> finish();

  std::uint32_t num_tiles() const { return static_cast<std::uint32_t>(parts_written_.size()); }

 private:
  std::vector<std::uint8_t> bytes_;
  std::vector<unsigned> parts_written_;   // per tile
  std::vector<unsigned> parts_declared_;  // per tile: nonzero TNsot seen, or 0
  bool finished_ = false;
};

// One tile-part for write_codestream.
struct TilePart {
  unsigned tile_index = 0;
  unsigned part_index = 0;
  unsigned num_parts = 1;
  std::vector<std::uint8_t> body;
};

// The whole codestream in one call: main header, the tile-parts in the order given, EOC.
std::vector<std::uint8_t> write_codestream(const MainHeader& header, const std::vector<TilePart>& parts);

}  // namespace codec::cs
