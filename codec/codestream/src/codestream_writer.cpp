#include "codec/codestream/codestream_writer.h"

#include <string>
#include <utility>

#include "codec/codestream/delimiters.h"
#include "codec/codestream/error.h"
#include "codec/codestream/tile_part.h"

namespace codec::cs {

CodestreamWriter::CodestreamWriter(const MainHeader& header) {
  ByteWriter out(bytes_);
  write_main_header(out, header);
  const std::uint32_t tiles = codec::cs::num_tiles(header.siz);
  parts_written_.assign(tiles, 0);
  parts_declared_.assign(tiles, 0);
}

void CodestreamWriter::add_tile_part(unsigned tile_index, unsigned part_index, unsigned num_parts,
                                     std::span<const std::uint8_t> body) {
  const std::string who = "tile-part " + std::to_string(part_index) + " of tile " + std::to_string(tile_index);
  if (finished_) throw CodestreamError(who + ": the codestream is already finished");
  if (tile_index >= parts_written_.size())
    throw CodestreamError(who + ": the image has only " + std::to_string(parts_written_.size()) + " tiles");
  if (part_index != parts_written_[tile_index])
    throw CodestreamError(who + ": expected tile-part " + std::to_string(parts_written_[tile_index]) +
                          " next, as tile-parts of a tile must come in order");
  unsigned& declared = parts_declared_[tile_index];
  if (num_parts != 0 && declared != 0 && num_parts != declared)
    throw CodestreamError(who + ": declares " + std::to_string(num_parts) + " tile-parts, an earlier part said " +
                          std::to_string(declared));
  // 14 = SOT segment (12) + SOD (2); Psot counts them with the body.
  if (body.size() > 0xFFFFFFFFu - 14)
    throw CodestreamError(who + ": " + std::to_string(body.size()) + " bytes of packet data overflow Psot");

  bytes_.reserve(bytes_.size() + body.size() + 16);  // SOT, SOD, the body and EOC: one allocation
  ByteWriter out(bytes_);
  const std::size_t sot = write_sot(out, Sot{tile_index, part_index, num_parts});
  write_sod(out);
  out.bytes(body);
  patch_psot(out, sot);

  ++parts_written_[tile_index];
  if (num_parts != 0) declared = num_parts;
}

std::vector<std::uint8_t> CodestreamWriter::finish() {
  if (finished_) throw CodestreamError("codestream: finish() called twice");
  for (std::size_t t = 0; t < parts_written_.size(); ++t) {
    if (parts_written_[t] == 0) throw CodestreamError("codestream: tile " + std::to_string(t) + " has no tile-part");
    if (parts_declared_[t] != 0 && parts_written_[t] != parts_declared_[t])
      throw CodestreamError("codestream: tile " + std::to_string(t) + " declares " +
                            std::to_string(parts_declared_[t]) + " tile-parts but " +
                            std::to_string(parts_written_[t]) + " were written");
  }
  ByteWriter out(bytes_);
  write_eoc(out);
  finished_ = true;
  std::vector<std::uint8_t> result = std::move(bytes_);
  bytes_.clear();
  return result;
}

std::vector<std::uint8_t> write_codestream(const MainHeader& header, const std::vector<TilePart>& parts) {
  CodestreamWriter writer(header);
  for (const TilePart& p : parts) writer.add_tile_part(p.tile_index, p.part_index, p.num_parts, p.body);
  return writer.finish();
}

}  // namespace codec::cs
