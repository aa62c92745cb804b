#include "packet_reader.h"

#include <algorithm>
#include <bit>
#include <string>

#include "byte_reader.h"
#include "codec/tier2/codeword_segments.h"

namespace codec::dec {

namespace {

// Packet-header bits (B.10.1): MSB first; after a 0xFF byte the next byte holds seven bits behind
// a stuffed 0.
class HeaderBitReader {
 public:
  HeaderBitReader(std::span<const std::uint8_t> data, std::size_t pos) : data_(data), pos_(pos) {}
  int bit() {
    if (bits_left_ == 0) {
      if (pos_ >= data_.size()) throw PacketTruncated("the stream ends inside a packet header");
      const bool after_ff = byte_ == 0xFF;
      byte_ = data_[pos_++];
      bits_left_ = after_ff ? 7 : 8;
    }
    --bits_left_;
    return (byte_ >> bits_left_) & 1;
  }
  std::uint32_t bits(int n) {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 1) | static_cast<std::uint32_t>(bit());
    return v;
  }
  // The header ends on a byte boundary; a final 0xFF is followed by the byte holding its stuffed bit.
  std::size_t end_position() const {
    if (bits_left_ == 0 && byte_ == 0xFF) return pos_ + 1;
    return pos_;
  }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_;
  std::uint8_t byte_ = 0;
  int bits_left_ = 0;
};

// Table B.4: the number of coding passes a packet adds for a code-block.
int read_pass_count(HeaderBitReader& in) {
  if (!in.bit()) return 1;
  if (!in.bit()) return 2;
  const int two = static_cast<int>(in.bits(2));
  if (two < 3) return 3 + two;
  const int five = static_cast<int>(in.bits(5));
  if (five < 31) return 6 + five;
  return 37 + static_cast<int>(in.bits(7));
}

int floor_log2(int n) { return std::bit_width(static_cast<unsigned>(n)) - 1; }

t2::BlockCoder coder_of(const PacketContext& ctx) { return ctx.ht ? t2::BlockCoder::Ht : t2::BlockCoder::Ebcot; }

bool segment_ends_after(const PacketContext& ctx, int pass) {
  return t2::segment_ends_after(ctx.style, pass, coder_of(ctx));
}

// The pieces (one length field each) the passes first_pass .. first_pass + count - 1 form.
std::vector<t2::SegmentPiece> split_passes(const PacketContext& ctx, int first_pass, int count) {
  return t2::split_into_segments(
      ctx.style, first_pass, count, [](int) { return std::size_t{0}; }, coder_of(ctx));
}

constexpr std::uint16_t kSop = 0xFF91, kEph = 0xFF92;

std::uint16_t u16_at(std::span<const std::uint8_t> d, std::size_t pos) {
  return pos + 1 < d.size() ? static_cast<std::uint16_t>((d[pos] << 8) | d[pos + 1]) : 0;
}

// A.7 / B.10.7: the most passes a block can have, all bit-planes of the deepest band (ROI shift
// included); a header asking for more is malformed.
constexpr int kMaxPasses = 3 * 300 + 1;

}  // namespace

TagTreeDecoder::TagTreeDecoder(int width, int height) {
  int w = width, h = height;
  std::size_t offset = 0;
  for (;;) {
    level_width_.push_back(w);
    level_offset_.push_back(offset);
    offset += static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    if (w <= 1 && h <= 1) break;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
  nodes_.resize(offset);
}

template <class BitSource>
bool TagTreeDecoder::walk(int x, int y, int threshold, BitSource& bits) {
  const int levels = static_cast<int>(level_width_.size());
  int inherited = 0;
  for (int l = levels - 1; l >= 0; --l) {
    Node& n =
        nodes_[level_offset_[static_cast<std::size_t>(l)] +
               static_cast<std::size_t>(y >> l) * static_cast<std::size_t>(level_width_[static_cast<std::size_t>(l)]) +
               static_cast<std::size_t>(x >> l)];
    // A node is never below its parent (each parent is the minimum of its children).
    if (n.low < inherited) n.low = inherited;
    while (!n.known && n.low < threshold) {
      if (bits.bit())
        n.known = true;
      else
        ++n.low;
    }
    if (n.low >= threshold) return false;
    inherited = n.low;
  }
  return true;
}

template <class BitSource>
bool TagTreeDecoder::below(int x, int y, int threshold, BitSource& bits) {
  return walk(x, y, threshold, bits);
}

template <class BitSource>
int TagTreeDecoder::value(int x, int y, int limit, BitSource& bits) {
  if (!walk(x, y, limit + 1, bits)) throw DecodeError("a tag-tree value exceeds " + std::to_string(limit));
  return nodes_[static_cast<std::size_t>(y) * static_cast<std::size_t>(level_width_[0]) + static_cast<std::size_t>(x)]
      .low;
}

std::size_t read_packet(std::span<const std::uint8_t> data, std::size_t pos, std::size_t file_offset,
                        const Precinct& precinct, int layer, std::vector<PrecinctBandTrees>& trees,
                        std::vector<BlockState>& blocks, const PacketContext& ctx) {
  // A.8.1: SOP may precede a packet when COD allows it.
  if (ctx.sop && u16_at(data, pos) == kSop) {
    if (pos + 6 > data.size()) throw PacketTruncated("the stream ends inside an SOP marker");
    if (u16_at(data, pos + 2) != 4) fail_at(file_offset + pos, "SOP length is not 4");
    pos += 6;
  }
  if (trees.empty())
    for (const PrecinctBand& pb : precinct.bands)
      trees.push_back(PrecinctBandTrees{TagTreeDecoder(pb.cols, pb.rows), TagTreeDecoder(pb.cols, pb.rows)});

  struct Contribution {
    std::size_t block;
    int first_pass;
    std::vector<t2::SegmentPiece> pieces;
  };
  std::vector<Contribution> contributions;
  const std::span<const std::uint8_t> header_bytes = ctx.packed ? ctx.packed->bytes : data;
  HeaderBitReader in(header_bytes, ctx.packed ? ctx.packed->pos : pos);
  {
    if (in.bit()) {  // B.10.3: 0 is an empty packet
      for (std::size_t b = 0; b < precinct.bands.size(); ++b) {
        const PrecinctBand& pb = precinct.bands[b];
        for (int j = 0; j < pb.rows; ++j)
          for (int i = 0; i < pb.cols; ++i) {
            const CodeBlock& cb = pb.blocks[static_cast<std::size_t>(j) * static_cast<std::size_t>(pb.cols) +
                                            static_cast<std::size_t>(i)];
            BlockState& st = blocks[cb.index];
            // B.10.4: inclusion through the tag tree until first included, then one bit.
            const bool first_time = !st.included;
            const bool included = first_time ? trees[b].inclusion.below(i, j, layer + 1, in) : in.bit() != 0;
            if (!included) continue;
            if (first_time) st.missing_msbs = trees[b].zero_bitplanes.value(i, j, 300, in);  // B.10.5
            const int added = read_pass_count(in);                                           // B.10.6
            int increase = 0;  // B.10.7.1: Lblock grows by the number of 1 bits before a 0
            while (in.bit()) {
              if (++increase + st.lblock > 32) fail_at(file_offset + pos, "a code-block's Lblock exceeds 32");
            }
            st.lblock += increase;
            const int first_pass = st.included ? st.passes : 0;
            if (first_pass + added > kMaxPasses)
              fail_at(file_offset + pos, "a code-block has more coding passes than bit-planes");
            // B.10.7.2: one length per codeword segment the new passes touch.
            auto pieces = split_passes(ctx, first_pass, added);
            for (t2::SegmentPiece& p : pieces) p.bytes = in.bits(st.lblock + floor_log2(p.passes));
            st.included = true;
            st.passes = first_pass + added;
            contributions.push_back(Contribution{cb.index, first_pass, std::move(pieces)});
          }
      }
    }
  }
  std::size_t header_end = in.end_position();
  // A.8.2: EPH follows the header when COD asks for it (in the packed headers when they are).
  if (ctx.eph && u16_at(header_bytes, header_end) == kEph) header_end += 2;
  if (ctx.packed)
    ctx.packed->pos = header_end;
  else
    pos = header_end;
  // The body: each contribution's bytes in header order.
  for (const Contribution& c : contributions) {
    BlockState& st = blocks[c.block];
    int pass = c.first_pass;
    for (const t2::SegmentPiece& p : c.pieces) {
      if (p.bytes > data.size() - std::min(pos, data.size()))
        throw PacketTruncated("the stream ends inside a packet body");
      // Kept only while every earlier pass was kept: tier-1 needs an unbroken run from pass 0.
      if (ctx.keep && st.kept_passes == pass) {
        st.data.insert(st.data.end(), data.begin() + static_cast<std::ptrdiff_t>(pos),
                       data.begin() + static_cast<std::ptrdiff_t>(pos + p.bytes));
        if (st.segment_open && !st.segments.empty()) {
          st.segments.back().bytes += p.bytes;
          st.segments.back().passes += p.passes;
        } else {
          st.segments.push_back(Segment{p.bytes, p.passes});
        }
        st.kept_passes += p.passes;
        st.segment_open = !segment_ends_after(ctx, pass + p.passes - 1);
      }
      pass += p.passes;
      pos += p.bytes;
    }
  }
  return pos;
}

}  // namespace codec::dec
