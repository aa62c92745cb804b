#include "codec/tier2/packet_writer.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "codec/tier2/codeword_segments.h"
#include "codec/tier2/pass_count_code.h"

namespace codec::t2 {

namespace {

// A tag-tree value no threshold reaches: blocks that never contribute stand out of the minima
// the trees send, so their parents carry only what the contributing blocks need.
constexpr int kNever = std::numeric_limits<int>::max();

[[noreturn]] void bad_plan(const std::string& what) { throw std::invalid_argument("PrecinctPacketWriter: " + what); }

void check_block(const CodeBlockCoding& b) {
  if (b.encoded == nullptr) bad_plan("code-block without an encoded block");
  const auto& passes = b.encoded->passes;
  std::size_t previous_length = 0;
  for (const t1::PassInfo& p : passes) {
    if (p.length < previous_length) bad_plan("pass lengths decrease");
    previous_length = p.length;
  }
  if (previous_length > b.encoded->data.size()) bad_plan("pass length beyond the block's data");
  int previous = 0;
  for (int c : b.cumulative_passes) {
    if (c < previous) bad_plan("cumulative pass counts decrease");
    if (static_cast<std::size_t>(c) > passes.size()) bad_plan("more passes planned than the block has");
    if (c - previous > kMaxPassesPerPacket) bad_plan("more than 164 passes in one packet (Table B.4)");
    previous = c;
  }
}

// First layer with passes, or kNever.
int first_layer(const CodeBlockCoding& b) {
  for (std::size_t l = 0; l < b.cumulative_passes.size(); ++l)
    if (b.cumulative_passes[l] > 0) return static_cast<int>(l);
  return kNever;
}

int floor_log2(int n) { return std::bit_width(static_cast<unsigned>(n)) - 1; }

void append_marker(std::vector<std::uint8_t>& out, std::uint8_t code) {
  out.push_back(0xFF);
  out.push_back(code);
}

}  // namespace

PrecinctPacketWriter::PrecinctPacketWriter(std::vector<PrecinctBand> bands, t1::BlockStyle style, BlockCoder coder)
    : bands_(std::move(bands)), style_(style), coder_(coder) {
  state_.reserve(bands_.size());
  for (const PrecinctBand& band : bands_) {
    if (band.cols < 0 || band.rows < 0) bad_plan("negative code-block count");
    if (band.blocks.size() != static_cast<std::size_t>(band.cols) * static_cast<std::size_t>(band.rows))
      bad_plan("band has " + std::to_string(band.blocks.size()) + " blocks, expected cols*rows");
    std::vector<int> inclusion, zero_bitplanes;
    for (const CodeBlockCoding& b : band.blocks) {
      check_block(b);
      const int layers = static_cast<int>(b.cumulative_passes.size());
      if (layers_ < 0) layers_ = layers;
      if (layers != layers_) bad_plan("code-blocks disagree on the number of layers");
      const int first = first_layer(b);
      if (first != kNever && b.encoded->missing_msbs < 0) bad_plan("negative missing MSBs");
      inclusion.push_back(first);
      zero_bitplanes.push_back(first == kNever ? kNever : b.encoded->missing_msbs);
    }
    state_.push_back(BandState{TagTreeEncoder(band.cols, band.rows, std::move(inclusion)),
                               TagTreeEncoder(band.cols, band.rows, std::move(zero_bitplanes)),
                               std::vector<BlockState>(band.blocks.size())});
  }
}

bool PrecinctPacketWriter::packet_is_empty(int layer) const {
  for (std::size_t b = 0; b < bands_.size(); ++b)
    for (std::size_t i = 0; i < bands_[b].blocks.size(); ++i)
      if (bands_[b].blocks[i].cumulative_passes[static_cast<std::size_t>(layer)] > state_[b].blocks[i].passes_sent)
        return false;
  return true;
}

std::size_t PrecinctPacketWriter::write_packet(int layer, bool sop, bool eph, std::uint16_t packet_sequence_number,
                                               std::vector<std::uint8_t>& out, bool copy_body) {
  const std::size_t start = out.size();
  if (layer != next_layer_)
    throw std::logic_error("PrecinctPacketWriter: layer " + std::to_string(layer) + " written, expected " +
                           std::to_string(next_layer_));
  if (layers_ >= 0 && layer >= layers_)
    throw std::logic_error("PrecinctPacketWriter: layer " + std::to_string(layer) + " beyond the plan's " +
                           std::to_string(layers_) + " layers");

  if (sop) {  // A.8.1: SOP, Lsop = 4, Nsop
    append_marker(out, 0x91);
    out.push_back(0x00);
    out.push_back(0x04);
    out.push_back(static_cast<std::uint8_t>(packet_sequence_number >> 8));
    out.push_back(static_cast<std::uint8_t>(packet_sequence_number & 0xFF));
  }

  body_.clear();
  HeaderBitWriter header(out);
  // B.10.3: a leading 0 announces an empty packet and ends the header there. Sent whenever no
  // block adds a pass: it is the shortest header, and leaves the tag trees untouched for later.
  if (packet_is_empty(layer)) {
    header.put_bit(false);
  } else {
    header.put_bit(true);
    for (std::size_t b = 0; b < bands_.size(); ++b) {
      const PrecinctBand& band = bands_[b];
      for (int y = 0; y < band.rows; ++y)
        for (int x = 0; x < band.cols; ++x)
          write_block_header(band.blocks[static_cast<std::size_t>(y) * band.cols + x], state_[b], x, y, layer, header);
    }
  }
  header.flush();
  if (eph) append_marker(out, 0x92);  // A.8.2
  // The body: the blocks' bytes straight from their codewords, in the header's order.
  std::size_t body_bytes = 0;
  for (const auto& piece : body_) body_bytes += piece.size();
  const std::size_t header_bytes = out.size() - start;
  if (copy_body) {
    out.reserve(out.size() + body_bytes);
    for (const auto& piece : body_) out.insert(out.end(), piece.begin(), piece.end());
  }
  ++next_layer_;
  return header_bytes + body_bytes;
}

void PrecinctPacketWriter::write_block_header(const CodeBlockCoding& plan, BandState& band, int x, int y, int layer,
                                              HeaderBitWriter& header) {
  BlockState& st = band.blocks[static_cast<std::size_t>(y) * band.inclusion.width() + x];
  const int first_pass = st.passes_sent;
  const int added = plan.cumulative_passes[static_cast<std::size_t>(layer)] - first_pass;

  // B.10.4 inclusion: a block not yet included answers through the inclusion tag tree
  // ("is your first layer <= this one?"); once included, one bit per packet.
  if (!st.included)
    band.inclusion.encode(x, y, layer + 1, header);
  else
    header.put_bit(added > 0);
  if (added == 0) return;

  // B.10.5: the zero bit-planes are sent once, completely, with the first inclusion.
  if (!st.included) band.zero_bitplanes.encode_value(x, y, header);

  write_pass_count(added, header);  // B.10.6

  // B.10.7: one length per codeword-segment piece, each in Lblock + floor(log2(passes in the
  // piece)) bits. Lblock grows (k ones then a zero raise it by k) to the least value that fits
  // every piece of this packet.
  const auto& passes = plan.encoded->passes;
  pieces_.clear();
  split_into_segments(
      style_, first_pass, added, [&](int pass) { return passes[static_cast<std::size_t>(pass)].length; }, coder_,
      pieces_);
  int lblock = st.lblock;
  for (const SegmentPiece& p : pieces_)
    lblock = std::max(lblock, static_cast<int>(std::bit_width(p.bytes)) - floor_log2(p.passes));
  for (int i = st.lblock; i < lblock; ++i) header.put_bit(true);
  header.put_bit(false);
  for (const SegmentPiece& p : pieces_) header.put_bits(p.bytes, lblock + floor_log2(p.passes));

  // The body carries the same bytes, in the same block order as the header.
  const std::size_t begin = first_pass == 0 ? 0 : passes[static_cast<std::size_t>(first_pass) - 1].length;
  const std::size_t end = passes[static_cast<std::size_t>(first_pass + added) - 1].length;
  body_.emplace_back(plan.encoded->data.data() + begin, end - begin);

  st.included = true;
  st.lblock = lblock;
  st.passes_sent = first_pass + added;
}

}  // namespace codec::t2
