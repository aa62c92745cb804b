#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "codec/t1/block_encoder.h"
#include "codec/t1/block_style.h"
#include "codec/tier2/codeword_segments.h"
#include "codec/tier2/tag_tree.h"

namespace codec::t2 {

// One code-block's contribution plan: how many of its coding passes are included after each layer.
// It owns nothing: the caller keeps the block and the counts alive while a writer holds the plan
// (rate control builds plans for thousands of blocks per trial, and a vector each was a third of
// a trial's time).
struct CodeBlockCoding {
  const t1::EncodedBlock* encoded = nullptr;  // never null; may have zero passes (all-zero block)
  std::span<const int> cumulative_passes;     // size = number of layers, non-decreasing, <= encoded->passes.size()
};

// A precinct's code-blocks in one subband, row-major cols x rows (either may be 0).
struct PrecinctBand {
  int cols = 0, rows = 0;
  std::vector<CodeBlockCoding> blocks;
};

// Writes the packets of one precinct (T.800 B.9, B.10), layer after layer. Tag trees and the
// per-block state (included before?, Lblock, passes sent) persist between layers, because every
// packet header codes only what the previous packets of the precinct have not told the decoder.
// Bands come in the packet's subband order (LL alone at resolution 0; HL, LH, HH above).
// The plan and each block's missing_msbs are read at construction (they fill the tag trees); the
// plan's pass counts and the EncodedBlocks' data and pass lengths are read when packets are
// written, so they must outlive the writer.
// Throws std::invalid_argument for an inconsistent plan, std::logic_error for layers out of order.
class PrecinctPacketWriter {
 public:
  // `coder`: which block coder made the blocks, for where their codeword segments end
  // (codeword_segments.h).
  PrecinctPacketWriter(std::vector<PrecinctBand> bands, t1::BlockStyle style, BlockCoder coder = BlockCoder::Ebcot);

  // Appends the packet for `layer` (layers must be written in order 0,1,2...): [SOP] header [EPH]
  // body. `packet_sequence_number` is SOP's Nsop (the packet's index in the tile, modulo 2^16).
  // With copy_body false the body is left out of `out` (rate control's trial sizes need only its
  // length). Returns the packet's length either way.
  std::size_t write_packet(int layer, bool sop, bool eph, std::uint16_t packet_sequence_number,
                           std::vector<std::uint8_t>& out, bool copy_body = true);

 private:
  struct BlockState {
    bool included = false;  // some earlier packet carried passes of this block
    int lblock = 3;         // B.10.7.1: starts at 3, only grows
    int passes_sent = 0;
  };
  struct BandState {
    TagTreeEncoder inclusion;       // value: first layer the block contributes to
    TagTreeEncoder zero_bitplanes;  // value: missing MSBs
    std::vector<BlockState> blocks;
  };

  bool packet_is_empty(int layer) const;
  void write_block_header(const CodeBlockCoding& plan, BandState& band, int x, int y, int layer,
                          HeaderBitWriter& header);

  std::vector<PrecinctBand> bands_;
  std::vector<BandState> state_;
  // The packet being written: each included block's new bytes, in header order (reused).
  std::vector<std::span<const std::uint8_t>> body_;
  std::vector<SegmentPiece> pieces_;  // the block being written: its length fields (reused)
  t1::BlockStyle style_;
  BlockCoder coder_;
  int layers_ = -1;  // from the plans; -1 while the precinct has no code-blocks
  int next_layer_ = 0;
};

}  // namespace codec::t2
