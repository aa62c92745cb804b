// Tier-2 (T.800 Annex B): tag trees, packet headers and bodies, progression orders. The read side
// of every structure is written here again from the standard, independently of the encoder, so
// the tests check the encoder against the decoder's view rather than against itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <cstdio>
#include <cstdint>
#include <memory>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "codec/t1/block_encoder.h"
#include "codec/t1/block_style.h"
#include "codec/tier2/header_bit_writer.h"
#include "codec/tier2/packet_writer.h"
#include "codec/tier2/progression.h"
#include "codec/tier2/tag_tree.h"

namespace {

using codec::t1::BlockStyle;
using codec::t1::EncodedBlock;
using codec::t1::PassInfo;
using codec::t2::CodeBlockCoding;
using codec::t2::ComponentGeometry;
using codec::t2::HeaderBitWriter;
using codec::t2::Order;
using codec::t2::PacketId;
using codec::t2::PrecinctBand;
using codec::t2::PrecinctPacketWriter;
using codec::t2::ResolutionGeometry;
using codec::t2::TagTreeEncoder;
using Bytes = std::vector<std::uint8_t>;

// ------------------------------------------------------------------------------------------------
// B.10.1 read side: bits MSB first; a byte after 0xFF holds 7 bits behind a stuffed 0.
class StuffedBitReader {
 public:
  StuffedBitReader(const Bytes& bytes, std::size_t pos) : bytes_(bytes), pos_(pos) {}

  int bit() {
    if (left_ == 0) {
      if (pos_ >= bytes_.size()) throw std::runtime_error("packet header runs past the data");
      byte_ = bytes_[pos_++];
      left_ = after_ff_ ? 7 : 8;
      if (after_ff_ && (byte_ & 0x80) != 0) throw std::runtime_error("stuffed bit after 0xFF is not 0");
      after_ff_ = byte_ == 0xFF;
      if (after_ff_) ++ff_bytes;
    }
    return (byte_ >> --left_) & 1;
  }
  std::uint64_t bits(int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = (v << 1) | static_cast<std::uint64_t>(bit());
    return v;
  }
  // Where the header ends: after the byte holding the last bit, or one further when that byte
  // was 0xFF (its 7 stuffed bits live in the next byte). Padding bits must be zero.
  std::size_t end() const {
    if (left_ > 0 && (byte_ & ((1u << left_) - 1)) != 0) throw std::runtime_error("non-zero header padding");
    if (left_ == 0 && after_ff_) {
      if (pos_ >= bytes_.size() || bytes_[pos_] != 0x00) throw std::runtime_error("header ends in 0xFF");
      return pos_ + 1;
    }
    return pos_;
  }

  int ff_bytes = 0;

 private:
  const Bytes& bytes_;
  std::size_t pos_;
  std::uint8_t byte_ = 0;
  int left_ = 0;
  bool after_ff_ = false;
};

// B.10.2 read side. Levels by halving (rounding up) down to one root; a node's lower bound starts
// at its parent's; reading 0 raises it, 1 fixes the value, until the bound reaches the threshold.
class TagTreeDecoder {
 public:
  TagTreeDecoder(int width, int height) {
    int w = width, h = height;
    if (w == 0 || h == 0) return;
    for (;;) {
      dims_.push_back({w, h});
      nodes_.emplace_back(static_cast<std::size_t>(w) * h);
      if (w == 1 && h == 1) break;
      w = (w + 1) / 2;
      h = (h + 1) / 2;
    }
  }
  // Whether leaf (x, y) is below `threshold`; if so value() is now exact.
  bool decode(int x, int y, int threshold, StuffedBitReader& in) {
    int bound = 0;
    for (int level = static_cast<int>(dims_.size()) - 1; level >= 0; --level) {
      Node& n = node(level, x >> level, y >> level);
      n.low = std::max(n.low, bound);
      while (!n.known && n.low < threshold) {
        if (in.bit() != 0)
          n.known = true;
        else
          ++n.low;
      }
      bound = n.low;
    }
    return node(0, x, y).known;
  }
  int value(int x, int y) { return node(0, x, y).low; }

 private:
  struct Node {
    int low = 0;
    bool known = false;
  };
  Node& node(int level, int x, int y) {
    return nodes_[static_cast<std::size_t>(level)]
                 [static_cast<std::size_t>(y) * dims_[static_cast<std::size_t>(level)].first + x];
  }
  std::vector<std::pair<int, int>> dims_;
  std::vector<std::vector<Node>> nodes_;
};

// ------------------------------------------------------------------------------------------------
// Bit writer.

TEST(HeaderBitWriter, PacksMsbFirstAndPads) {
  Bytes out;
  HeaderBitWriter w(out);
  w.put_bits(0b1011, 4);
  w.put_bits(0b0110, 4);
  w.put_bits(0b101, 3);
  w.flush();
  EXPECT_EQ(out, (Bytes{0xB6, 0xA0}));
}

TEST(HeaderBitWriter, StuffsAZeroBitAfterFF) {
  Bytes out;
  HeaderBitWriter w(out);
  w.put_bits(0xFFFF, 16);  // 8 ones -> FF; then 7 ones -> 7F (stuffed 0 first); the last one -> 80
  w.flush();
  EXPECT_EQ(out, (Bytes{0xFF, 0x7F, 0x80}));
}

TEST(HeaderBitWriter, NeverEndsInFF) {
  Bytes out;
  HeaderBitWriter w(out);
  w.put_bits(0xFF, 8);
  w.flush();
  EXPECT_EQ(out, (Bytes{0xFF, 0x00}));  // B.10.1: the stuffed bit's byte is kept
  // Reuse after flush starts a fresh byte with 8 bits.
  w.put_bits(0xFF, 8);
  w.put_bit(true);
  w.flush();
  EXPECT_EQ(out, (Bytes{0xFF, 0x00, 0xFF, 0x40}));
}

TEST(HeaderBitWriter, RandomBitsRoundTrip) {
  std::mt19937 rng(7);
  for (int round = 0; round < 200; ++round) {
    std::vector<int> bits(rng() % 300);
    // Runs of ones make 0xFF bytes likely.
    for (int& b : bits) b = (rng() % 8) != 0;
    Bytes out{0x12};  // bytes already there are left alone
    HeaderBitWriter w(out);
    for (int b : bits) w.put_bit(b != 0);
    w.flush();
    ASSERT_EQ(out[0], 0x12);
    StuffedBitReader r(out, 1);
    for (int b : bits) ASSERT_EQ(r.bit(), b);
    if (!bits.empty()) {
      EXPECT_EQ(r.end(), out.size());
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Tag trees.

// The example of T.800 B.10.2 (Figure B.12 and the NOTE after it): a 6x3 array with
//   q3 = 1 3 2 3 2 3 / 2 2 1 4 3 2 / 2 2 2 2 1 2, so q2 = 1 1 2 / 2 2 1, q1 = 1 1, q0 = 1.
// Coding q3(0,0), q3(1,0), q3(2,0) completely (threshold beyond every value) gives
//   q3(0,0) = 1: root 0 1 (q0 > 0, q0 = 1), then q1(0,0) 1, q2(0,0) 1, q3(0,0) 1  -> 01111
//   q3(1,0) = 3: ancestors already known = 1; leaf 0 0 1 (> 1, > 2, = 3)            -> 001
//   q3(2,0) = 2: q2(1,0) = 1 learnt with one 1; leaf 0 1 (> 1, = 2)                 -> 101
TEST(TagTree, StandardExampleBitByBit) {
  TagTreeEncoder tree(6, 3, {1, 3, 2, 3, 2, 3, 2, 2, 1, 4, 3, 2, 2, 2, 2, 2, 1, 2});
  Bytes out;
  HeaderBitWriter w(out);
  tree.encode(0, 0, 100, w);
  EXPECT_EQ(w.bits_written(), 5u);
  tree.encode(1, 0, 100, w);
  EXPECT_EQ(w.bits_written(), 8u);
  tree.encode(2, 0, 100, w);
  EXPECT_EQ(w.bits_written(), 11u);
  w.flush();
  // 01111 001 101 -> 0111 1001 | 101 + padding
  EXPECT_EQ(out, (Bytes{0x79, 0xA0}));
}

// The inclusion bits of T.800 Table B.5 (3x2 code-blocks, first layer, threshold 1): blocks (0,0)
// and (1,0) are included in layer 0, the others later (their exact layers do not matter here).
//   (0,0): root = 0 -> 1, q1(0,0) = 0 -> 1, leaf -> 1          111
//   (1,0): ancestors known; leaf = 0                              1
//   (2,0): q1(1,0) >= 1 -> 0 and the bound reaches 1; leaf silent 0
//   (0,1), (1,1): leaf >= 1 -> 0 each                             0 0
//   (2,1): its parent already said >= 1: nothing                  -
TEST(TagTree, StandardInclusionExample) {
  TagTreeEncoder tree(3, 2, {0, 0, 1, 2, 1, 3});
  Bytes out;
  HeaderBitWriter w(out);
  std::vector<std::uint64_t> after;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      tree.encode(x, y, 1, w);
      after.push_back(w.bits_written());
    }
  EXPECT_EQ(after, (std::vector<std::uint64_t>{3, 4, 5, 6, 7, 7}));
  w.flush();
  EXPECT_EQ(out, (Bytes{0xF0}));  // 1111000 + padding
}

// Encodes random arrays the way packet headers query them and decodes them independently.
void tag_tree_round_trip(int width, int height, std::mt19937& rng) {
  const int max_value = 1 + static_cast<int>(rng() % 9);
  std::vector<int> values(static_cast<std::size_t>(width) * height);
  for (int& v : values) v = static_cast<int>(rng() % (max_value + 1));
  TagTreeEncoder enc(width, height, values);
  TagTreeDecoder dec(width, height);
  Bytes out;
  HeaderBitWriter w(out);

  // Inclusion style: at each rising threshold, query every leaf not yet known, in raster order.
  std::vector<bool> known(values.size(), false);
  std::vector<std::vector<bool>> expect_known;
  for (int t = 1; t <= max_value + 2; ++t) {
    std::vector<bool> row;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        if (known[i]) continue;
        enc.encode(x, y, t, w);
        known[i] = values[i] < t;
        row.push_back(known[i]);
      }
    expect_known.push_back(row);
  }
  // Then a second tree coded completely leaf by leaf (zero bit-plane style), random order.
  TagTreeEncoder enc2(width, height, values);
  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  for (int i : order) enc2.encode_value(i % width, i / width, w);
  w.flush();

  StuffedBitReader r(out, 0);
  std::fill(known.begin(), known.end(), false);
  for (int t = 1; t <= max_value + 2; ++t) {
    std::size_t j = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        if (known[i]) continue;
        known[i] = dec.decode(x, y, t, r);
        ASSERT_EQ(known[i], expect_known[static_cast<std::size_t>(t - 1)][j++]) << width << "x" << height << " t=" << t;
        if (known[i]) {
          ASSERT_EQ(dec.value(x, y), values[i]);
        }
      }
  }
  TagTreeDecoder dec2(width, height);
  for (int i : order) {
    int t = 1;
    while (!dec2.decode(i % width, i / width, t, r)) ++t;
    ASSERT_EQ(dec2.value(i % width, i / width), values[static_cast<std::size_t>(i)]);
  }
  EXPECT_EQ(r.end(), out.size());
}

TEST(TagTree, RoundTripsManyShapes) {
  std::mt19937 rng(2024);
  const std::vector<std::pair<int, int>> shapes = {{1, 1}, {1, 7}, {9, 1}, {1, 33},  {33, 1},
                                                   {5, 3}, {3, 5}, {2, 2}, {16, 16}, {7, 13}};
  for (auto [w, h] : shapes)
    for (int round = 0; round < 30; ++round) {
      tag_tree_round_trip(w, h, rng);
      if (HasFatalFailure()) return;
    }
}

TEST(TagTree, RejectsBadInput) {
  EXPECT_THROW(TagTreeEncoder(2, 2, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(TagTreeEncoder(1, 2, {1, -2}), std::invalid_argument);
  TagTreeEncoder empty(0, 4, {});
  EXPECT_EQ(empty.width(), 0);
}

// ------------------------------------------------------------------------------------------------
// Packets.

// Where a codeword segment ends (B.10.7.2), stated as the standard reasons about it: with
// terminate-each-pass every pass is terminated; with bypass, a segment ends wherever the coder
// changes between MQ and raw. Raw passes are the significance and refinement passes from the
// 11th pass on (pass index p >= 10 with p % 3 != 0, p % 3 == 0 being a cleanup pass).
bool test_segment_ends(const BlockStyle& s, int pass) {
  if (s.terminate_each_pass) return true;
  if (!s.bypass) return false;
  auto raw = [](int p) { return p >= 10 && p % 3 != 0; };
  return raw(pass) != raw(pass + 1);
}

int floor_log2(int n) {
  int k = 0;
  while ((n >> (k + 1)) != 0) ++k;
  return k;
}

// Table B.4 read side.
int read_pass_count(StuffedBitReader& in) {
  if (in.bit() == 0) return 1;
  if (in.bit() == 0) return 2;
  const int two = static_cast<int>(in.bits(2));
  if (two != 3) return 3 + two;
  const int five = static_cast<int>(in.bits(5));
  if (five != 31) return 6 + five;
  return 37 + static_cast<int>(in.bits(7));
}

struct Contribution {
  bool included = false;
  int first_inclusion_layer = -1;  // decoded from the inclusion tag tree, on first inclusion
  int zero_bitplanes = -1;         // only on first inclusion
  int passes = 0;
  std::vector<std::uint64_t> lengths;
  Bytes bytes;
};

struct DecodedPacket {
  bool empty = true;
  std::vector<std::vector<Contribution>> blocks;  // [band][block]
  std::size_t header_bytes = 0;
};

// Everything B.10 asks of a decoder, for one precinct across its layers.
class TestPrecinctReader {
 public:
  TestPrecinctReader(const std::vector<std::pair<int, int>>& band_shapes, BlockStyle style) : style_(style) {
    for (auto [cols, rows] : band_shapes)
      bands_.push_back(Band{cols, rows, TagTreeDecoder(cols, rows), TagTreeDecoder(cols, rows),
                            std::vector<State>(static_cast<std::size_t>(cols) * rows)});
  }

  DecodedPacket read(const Bytes& s, std::size_t& pos, int layer, bool sop, bool eph, std::uint16_t nsop,
                     int* ff_bytes) {
    DecodedPacket p;
    if (sop) {
      const Bytes expect{0xFF, 0x91, 0x00, 0x04, static_cast<std::uint8_t>(nsop >> 8), static_cast<std::uint8_t>(nsop)};
      if (pos + 6 > s.size() || !std::equal(expect.begin(), expect.end(), s.begin() + static_cast<std::ptrdiff_t>(pos)))
        throw std::runtime_error("missing or wrong SOP");
      pos += 6;
    }
    const std::size_t header_start = pos;
    StuffedBitReader in(s, pos);
    p.empty = in.bit() == 0;
    for (Band& band : bands_) {
      p.blocks.emplace_back(band.states.size());
      if (p.empty) continue;
      for (int y = 0; y < band.rows; ++y)
        for (int x = 0; x < band.cols; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * band.cols + x;
          State& st = band.states[i];
          Contribution& c = p.blocks.back()[i];
          const bool first = !st.included;
          c.included = first ? band.inclusion.decode(x, y, layer + 1, in) : in.bit() != 0;
          if (!c.included) continue;
          if (first) {
            c.first_inclusion_layer = band.inclusion.value(x, y);
            int t = 1;
            while (!band.zero_bitplanes.decode(x, y, t, in)) ++t;
            c.zero_bitplanes = band.zero_bitplanes.value(x, y);
          }
          c.passes = read_pass_count(in);
          while (in.bit() != 0) ++st.lblock;
          int run = 0;
          for (int pass = st.passes; pass < st.passes + c.passes; ++pass) {
            ++run;
            if (pass == st.passes + c.passes - 1 || test_segment_ends(style_, pass)) {
              c.lengths.push_back(in.bits(st.lblock + floor_log2(run)));
              run = 0;
            }
          }
          st.included = true;
          st.passes += c.passes;
        }
    }
    pos = in.end();
    p.header_bytes = pos - header_start;
    if (ff_bytes != nullptr) *ff_bytes += in.ff_bytes;
    if (eph) {
      if (pos + 2 > s.size() || s[pos] != 0xFF || s[pos + 1] != 0x92) throw std::runtime_error("missing EPH");
      pos += 2;
    }
    for (auto& band : p.blocks)
      for (Contribution& c : band) {
        const std::uint64_t total = std::accumulate(c.lengths.begin(), c.lengths.end(), std::uint64_t{0});
        if (pos + total > s.size()) throw std::runtime_error("packet body runs past the data");
        c.bytes.assign(s.begin() + static_cast<std::ptrdiff_t>(pos),
                       s.begin() + static_cast<std::ptrdiff_t>(pos + total));
        pos += total;
      }
    return p;
  }

 private:
  struct State {
    bool included = false;
    int lblock = 3;
    int passes = 0;
  };
  struct Band {
    int cols, rows;
    TagTreeDecoder inclusion, zero_bitplanes;
    std::vector<State> states;
  };
  BlockStyle style_;
  std::vector<Band> bands_;
};

// A precinct plan with its fake tier-1 output.
// A plan for one block whose pass counts live as long as the test program (CodeBlockCoding owns
// nothing).
CodeBlockCoding coding(const EncodedBlock* block, const std::vector<int>& cumulative_passes) {
  static std::deque<std::vector<int>> kept;
  return CodeBlockCoding{block, kept.emplace_back(cumulative_passes)};
}

struct Plan {
  std::vector<std::unique_ptr<EncodedBlock>> storage;
  std::deque<std::vector<int>> pass_counts;  // what the plans' spans refer to (a deque: never moves)
  std::vector<PrecinctBand> bands;
  int layers = 0;
};

EncodedBlock fake_block(std::mt19937& rng, const BlockStyle& style) {
  EncodedBlock b;
  b.missing_msbs = static_cast<int>(rng() % 16);
  const unsigned kind = rng() % 10;
  const int passes = kind == 0 ? 0 : kind == 1 ? 120 + static_cast<int>(rng() % 80) : 1 + static_cast<int>(rng() % 40);
  std::size_t length = 0;
  for (int i = 0; i < passes; ++i) {
    const unsigned r = rng() % 40;
    if (r == 0)
      length += 300 + rng() % 20000;  // forces Lblock up
    else if (r < 8)
      length += 0;  // a pass that adds no byte
    else
      length += rng() % 60;
    b.passes.push_back(PassInfo{length, 1.0, i == passes - 1 || test_segment_ends(style, i)});
  }
  b.data.resize(length);
  for (auto& byte : b.data) byte = static_cast<std::uint8_t>(rng() % 5 == 0 ? 0xFF : rng());
  return b;
}

Plan random_plan(std::mt19937& rng, const BlockStyle& style) {
  Plan plan;
  plan.layers = 1 + static_cast<int>(rng() % 6);
  const int nbands = rng() % 8 == 0 ? 0 : (rng() % 2 == 0 ? 1 : 3);
  const int dead_layer = rng() % 2 == 0 ? static_cast<int>(rng() % plan.layers) : -1;  // forces an empty packet
  for (int b = 0; b < nbands; ++b) {
    PrecinctBand band;
    band.cols = static_cast<int>(rng() % 5);
    band.rows = static_cast<int>(rng() % 5);
    for (int i = 0; i < band.cols * band.rows; ++i) {
      plan.storage.push_back(std::make_unique<EncodedBlock>(fake_block(rng, style)));
      const EncodedBlock& enc = *plan.storage.back();
      CodeBlockCoding cb;
      cb.encoded = &enc;
      std::vector<int>& cumulative = plan.pass_counts.emplace_back();
      const int n = static_cast<int>(enc.passes.size());
      const unsigned mode = rng() % 5;  // 0: never included; 1: late start; else from a random layer
      const int start = mode == 1 ? plan.layers - 1 : static_cast<int>(rng() % plan.layers);
      int sent = 0;
      for (int l = 0; l < plan.layers; ++l) {
        int add = 0;
        if (mode != 0 && l >= start && l != dead_layer && sent < n) {
          const int cap = std::min(164, n - sent);
          add = rng() % 3 == 0 ? 0 : 1 + static_cast<int>(rng() % cap);
          if (l == plan.layers - 1 && rng() % 2 == 0) add = cap;
        }
        sent += add;
        cumulative.push_back(sent);
      }
      cb.cumulative_passes = cumulative;
      band.blocks.push_back(cb);
    }
    plan.bands.push_back(std::move(band));
  }
  return plan;
}

struct Coverage {
  int packets = 0, empty_packets = 0, ff_header_bytes = 0, multi_piece = 0, first_inclusions = 0, long_pass_codes = 0,
      late_inclusions = 0;
};

// Writes every layer of a random plan and checks each field the independent reader recovers.
void check_plan(const Plan& plan, const BlockStyle& style, std::mt19937& rng, Coverage& cov) {
  PrecinctPacketWriter writer(plan.bands, style);
  std::vector<std::pair<int, int>> shapes;
  for (const PrecinctBand& b : plan.bands) shapes.emplace_back(b.cols, b.rows);
  TestPrecinctReader reader(shapes, style);

  Bytes stream;
  std::vector<std::tuple<bool, bool, std::uint16_t>> markers;
  for (int l = 0; l < plan.layers; ++l) {
    const bool sop = rng() % 2 == 0, eph = rng() % 2 == 0;
    const auto nsop = static_cast<std::uint16_t>(rng());
    markers.emplace_back(sop, eph, nsop);
    writer.write_packet(l, sop, eph, nsop, stream);
  }

  std::size_t pos = 0;
  for (int l = 0; l < plan.layers; ++l) {
    auto [sop, eph, nsop] = markers[static_cast<std::size_t>(l)];
    const DecodedPacket p = reader.read(stream, pos, l, sop, eph, nsop, &cov.ff_header_bytes);
    ++cov.packets;
    bool any = false;
    for (std::size_t b = 0; b < plan.bands.size(); ++b)
      for (std::size_t i = 0; i < plan.bands[b].blocks.size(); ++i) {
        const CodeBlockCoding& cb = plan.bands[b].blocks[i];
        const int before = l == 0 ? 0 : cb.cumulative_passes[static_cast<std::size_t>(l - 1)];
        const int added = cb.cumulative_passes[static_cast<std::size_t>(l)] - before;
        const Contribution& c = p.blocks[b][i];
        any = any || added > 0;
        SCOPED_TRACE("layer " + std::to_string(l) + " band " + std::to_string(b) + " block " + std::to_string(i));
        ASSERT_EQ(c.included, added > 0);
        if (added == 0) continue;
        const bool first = before == 0;
        if (first) {
          ++cov.first_inclusions;
          if (l > 0) ++cov.late_inclusions;
          ASSERT_EQ(c.first_inclusion_layer, l);
          ASSERT_EQ(c.zero_bitplanes, cb.encoded->missing_msbs);
        } else {
          ASSERT_EQ(c.zero_bitplanes, -1);
        }
        ASSERT_EQ(c.passes, added);
        if (added >= 37) ++cov.long_pass_codes;
        // Expected pieces straight from the pass lengths.
        const auto& passes = cb.encoded->passes;
        auto upto = [&](int pass) -> std::uint64_t {
          return pass < 0 ? 0 : passes[static_cast<std::size_t>(pass)].length;
        };
        std::vector<std::uint64_t> expect;
        int start = before;
        for (int pass = before; pass < before + added; ++pass)
          if (pass == before + added - 1 || test_segment_ends(style, pass)) {
            expect.push_back(upto(pass) - upto(start - 1));
            start = pass + 1;
          }
        ASSERT_EQ(c.lengths, expect);
        if (expect.size() > 1) ++cov.multi_piece;
        const Bytes slice(cb.encoded->data.begin() + static_cast<std::ptrdiff_t>(upto(before - 1)),
                          cb.encoded->data.begin() + static_cast<std::ptrdiff_t>(upto(before + added - 1)));
        ASSERT_EQ(c.bytes, slice);
      }
    // The writer uses the empty-packet bit exactly when nothing is added (one byte of header).
    ASSERT_EQ(p.empty, !any) << "layer " << l;
    if (p.empty) {
      ++cov.empty_packets;
      ASSERT_EQ(p.header_bytes, 1u);
    }
  }
  ASSERT_EQ(pos, stream.size());
}

class PacketRoundTrip : public ::testing::TestWithParam<int> {};

BlockStyle style_variant(int v) {
  BlockStyle s;
  s.bypass = v == 2 || v == 3;
  s.terminate_each_pass = v == 1 || v == 3;
  return s;
}

TEST_P(PacketRoundTrip, RandomPlansDecodeIndependently) {
  const BlockStyle style = style_variant(GetParam());
  std::mt19937 rng(1000 + GetParam());
  Coverage cov;
  for (int round = 0; round < 400; ++round) {
    const Plan plan = random_plan(rng, style);
    check_plan(plan, style, rng, cov);
    if (HasFatalFailure()) {
      ADD_FAILURE() << "round " << round;
      return;
    }
  }
  // The random plans did reach the cases they are meant to reach.
  std::printf(
      "packets %d, empty %d, 0xFF header bytes %d, first inclusions %d (late %d), 37+ pass codes %d, multi-piece %d\n",
      cov.packets, cov.empty_packets, cov.ff_header_bytes, cov.first_inclusions, cov.late_inclusions,
      cov.long_pass_codes, cov.multi_piece);
  EXPECT_GT(cov.empty_packets, 50);
  EXPECT_GT(cov.ff_header_bytes, 10);
  EXPECT_GT(cov.late_inclusions, 50);
  EXPECT_GT(cov.long_pass_codes, 10);
  if (style.bypass || style.terminate_each_pass) {
    EXPECT_GT(cov.multi_piece, 50);
  }
}

std::string style_name(const ::testing::TestParamInfo<int>& info) {
  static const char* const names[] = {"plain", "terminate_each_pass", "bypass", "bypass_terminate"};
  return names[info.param];
}

INSTANTIATE_TEST_SUITE_P(Styles, PacketRoundTrip, ::testing::Values(0, 1, 2, 3), style_name);

EncodedBlock block_with_lengths(std::vector<std::size_t> lengths, int missing_msbs) {
  EncodedBlock b;
  b.missing_msbs = missing_msbs;
  for (std::size_t len : lengths) b.passes.push_back(PassInfo{len, 0.0, false});
  b.data.resize(lengths.empty() ? 0 : lengths.back());
  for (std::size_t i = 0; i < b.data.size(); ++i) b.data[i] = static_cast<std::uint8_t>(i + 1);
  return b;
}

// A hand-worked pair of packets for one 1x1 band.
// Layer 0 adds pass 0 (5 bytes), missing MSBs 2:
//   1 non-empty | 1 inclusion tree (value 0 < 1) | 001 zero bit-planes = 2 | 0 one pass |
//   0 Lblock stays 3 | 101 length 5 in 3 + log2(1) bits         -> 1100 1001 01 -> C9 40
// Layer 1 adds passes 1-2 (cumulative 45, so 40 bytes):
//   1 non-empty | 1 included again | 10 two passes | 110 Lblock 3 -> 5 (40 needs 6 bits =
//   5 + log2(2)) | 101000 length 40                                -> 1110 1101 0100 0 -> ED 40
TEST(PacketWriter, HandWorkedHeaders) {
  const EncodedBlock enc = block_with_lengths({5, 20, 45}, 2);
  PrecinctBand band{1, 1, {coding(&enc, {1, 3})}};
  PrecinctPacketWriter writer({band}, BlockStyle{});
  Bytes out;
  writer.write_packet(0, false, false, 0, out);
  Bytes expect{0xC9, 0x40, 1, 2, 3, 4, 5};
  EXPECT_EQ(out, expect);
  out.clear();
  writer.write_packet(1, true, true, 0x1234, out);
  expect = {0xFF, 0x91, 0x00, 0x04, 0x12, 0x34, 0xED, 0x40, 0xFF, 0x92};
  for (int i = 6; i <= 45; ++i) expect.push_back(static_cast<std::uint8_t>(i));
  EXPECT_EQ(out, expect);
}

// With bypass, 12 passes sent at once split after pass 9 (MQ) and pass 11 (raw): pieces of
// 10 and 2 passes; the lengths take Lblock + 3 and Lblock + 1 bits.
TEST(PacketWriter, BypassSplitsAfterTheFourthBitPlane) {
  std::vector<std::size_t> lengths;
  for (int i = 1; i <= 12; ++i) lengths.push_back(static_cast<std::size_t>(i));
  const EncodedBlock enc = block_with_lengths(lengths, 0);
  BlockStyle style;
  style.bypass = true;
  PrecinctPacketWriter writer({PrecinctBand{1, 1, {coding(&enc, {12})}}}, style);
  Bytes out;
  writer.write_packet(0, false, false, 0, out);
  // 1 non-empty | 1 inclusion | 1 zero bit-planes = 0 | 1111 00110 twelve passes | 0 Lblock stays 3
  // (10 needs 4 bits <= 3 + log2(10); 2 needs 2 <= 3 + log2(2)) | 10 in 6 bits 001010 |
  // 2 in 4 bits 0010, then the 12 body bytes.
  // 1111 1110 | 0110 0001 | 0100 010 + padding  -> FE 61 44
  Bytes expect{0xFE, 0x61, 0x44};
  for (int i = 0; i < 12; ++i) expect.push_back(static_cast<std::uint8_t>(i + 1));
  EXPECT_EQ(out, expect);
}

// An HT block's cleanup, SigProp and MagRef passes in one packet (T.814 Annex B): the cleanup is one
// codeword segment and the two refinement passes another, so two lengths follow: 5 in Lblock = 3
// bits, 15 in Lblock + floor(log2 2) = 4 bits. (As one EBCOT segment, 20 bytes in 3 + 1 bits would
// need Lblock raised.)
TEST(PacketWriter, HtBlocksSignalCleanupAndRefinementSegments) {
  const EncodedBlock enc = block_with_lengths({5, 9, 20}, 0);
  PrecinctPacketWriter writer({PrecinctBand{1, 1, {coding(&enc, {3})}}}, BlockStyle{}, codec::t2::BlockCoder::Ht);
  Bytes out;
  writer.write_packet(0, false, false, 0, out);
  // 1 non-empty | 1 inclusion | 1 zero bit-planes = 0 | 1100 three passes | 0 Lblock stays 3 |
  // 101 | 1111, padded: 1111 1000 | 1011 1110 -> F8 BE, then the 20 body bytes.
  Bytes expect{0xF8, 0xBE};
  for (int i = 1; i <= 20; ++i) expect.push_back(static_cast<std::uint8_t>(i));
  EXPECT_EQ(out, expect);
  EXPECT_TRUE(codec::t2::segment_ends_after(BlockStyle{}, 0, codec::t2::BlockCoder::Ht));
  EXPECT_FALSE(codec::t2::segment_ends_after(BlockStyle{}, 1, codec::t2::BlockCoder::Ht));
  EXPECT_TRUE(codec::t2::segment_ends_after(BlockStyle{}, 2, codec::t2::BlockCoder::Ht));
}

TEST(PacketWriter, EmptyPrecinctsAndOrderChecks) {
  PrecinctPacketWriter none({}, BlockStyle{});
  Bytes out;
  none.write_packet(0, false, true, 0, out);
  none.write_packet(1, false, false, 0, out);
  EXPECT_EQ(out, (Bytes{0x00, 0xFF, 0x92, 0x00}));
  EXPECT_THROW(none.write_packet(3, false, false, 0, out), std::logic_error);

  PrecinctPacketWriter zero_blocks({PrecinctBand{0, 3, {}}, PrecinctBand{2, 0, {}}}, BlockStyle{});
  out.clear();
  zero_blocks.write_packet(0, false, false, 0, out);
  EXPECT_EQ(out, (Bytes{0x00}));

  const EncodedBlock enc = block_with_lengths({1, 2}, 0);
  PrecinctPacketWriter one({PrecinctBand{1, 1, {coding(&enc, {0, 2})}}}, BlockStyle{});
  out.clear();
  EXPECT_THROW(one.write_packet(1, false, false, 0, out), std::logic_error);  // layer 0 first
  one.write_packet(0, false, false, 0, out);
  one.write_packet(1, false, false, 0, out);
  EXPECT_THROW(one.write_packet(2, false, false, 0, out), std::logic_error);  // only 2 layers
}

TEST(PacketWriter, RejectsInconsistentPlans) {
  const EncodedBlock enc = block_with_lengths({1, 2, 3}, 0);
  auto make = [&](std::vector<int> cum) {
    return PrecinctPacketWriter({PrecinctBand{1, 1, {coding(&enc, cum)}}}, BlockStyle{});
  };
  EXPECT_THROW(make({2, 1}), std::invalid_argument);  // decreasing
  EXPECT_THROW(make({4}), std::invalid_argument);     // more passes than coded
  EXPECT_THROW(PrecinctPacketWriter({PrecinctBand{2, 1, {coding(&enc, {1})}}}, BlockStyle{}),
               std::invalid_argument);  // 1 block for 2x1
  EXPECT_THROW(PrecinctPacketWriter({PrecinctBand{1, 1, {coding(nullptr, {0})}}}, BlockStyle{}), std::invalid_argument);
  EXPECT_THROW(PrecinctPacketWriter({PrecinctBand{2, 1, {coding(&enc, {1}), coding(&enc, {1, 2})}}}, BlockStyle{}),
               std::invalid_argument);  // layer counts disagree
  std::vector<std::size_t> many(200, 1);
  const EncodedBlock big = block_with_lengths(many, 0);
  EXPECT_THROW(PrecinctPacketWriter({PrecinctBand{1, 1, {coding(&big, {165})}}}, BlockStyle{}),
               std::invalid_argument);  // Table B.4 stops at 164
  EXPECT_NO_THROW(PrecinctPacketWriter({PrecinctBand{1, 1, {coding(&big, {164, 200})}}}, BlockStyle{}));
}

// ------------------------------------------------------------------------------------------------
// Progression.

std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return (a + b - 1) / b; }

struct Tile {
  std::int64_t x0, y0, x1, y1;
};
struct CompSpec {
  int dx, dy;
  std::vector<std::pair<int, int>> pp;  // (PPx, PPy) per resolution; NL = size - 1
};

// B.5 / B.6: tile-component, resolution rectangles and precinct counts.
std::vector<ComponentGeometry> geometry(const Tile& t, const std::vector<CompSpec>& specs) {
  std::vector<ComponentGeometry> comps;
  for (const CompSpec& s : specs) {
    ComponentGeometry c;
    c.dx = s.dx;
    c.dy = s.dy;
    const std::int64_t tcx0 = ceil_div(t.x0, s.dx), tcx1 = ceil_div(t.x1, s.dx);
    const std::int64_t tcy0 = ceil_div(t.y0, s.dy), tcy1 = ceil_div(t.y1, s.dy);
    const int nl = static_cast<int>(s.pp.size()) - 1;
    for (int r = 0; r <= nl; ++r) {
      ResolutionGeometry g;
      const std::int64_t d = std::int64_t{1} << (nl - r);
      g.x0 = ceil_div(tcx0, d);
      g.x1 = ceil_div(tcx1, d);
      g.y0 = ceil_div(tcy0, d);
      g.y1 = ceil_div(tcy1, d);
      g.ppx = s.pp[static_cast<std::size_t>(r)].first;
      g.ppy = s.pp[static_cast<std::size_t>(r)].second;
      const std::int64_t px = std::int64_t{1} << g.ppx, py = std::int64_t{1} << g.ppy;
      g.precincts_wide = g.x1 > g.x0 ? static_cast<int>(ceil_div(g.x1, px) - g.x0 / px) : 0;
      g.precincts_high = g.y1 > g.y0 ? static_cast<int>(ceil_div(g.y1, py) - g.y0 / py) : 0;
      c.resolutions.push_back(g);
    }
    comps.push_back(c);
  }
  return comps;
}

int count(const ComponentGeometry& c, int r) {
  const ResolutionGeometry& g = c.resolutions[static_cast<std::size_t>(r)];
  return g.precincts_wide * g.precincts_high;
}

std::vector<PacketId> nested_lrcp_or_rlcp(bool layer_first, int layers, const std::vector<ComponentGeometry>& comps) {
  int max_r = 0;
  for (const auto& c : comps) max_r = std::max(max_r, static_cast<int>(c.resolutions.size()));
  std::vector<PacketId> out;
  const int outer = layer_first ? layers : max_r, inner = layer_first ? max_r : layers;
  for (int a = 0; a < outer; ++a)
    for (int b = 0; b < inner; ++b) {
      const int l = layer_first ? a : b, r = layer_first ? b : a;
      for (int c = 0; c < static_cast<int>(comps.size()); ++c) {
        if (r >= static_cast<int>(comps[static_cast<std::size_t>(c)].resolutions.size())) continue;
        for (int k = 0; k < count(comps[static_cast<std::size_t>(c)], r); ++k) out.push_back({l, r, c, k});
      }
    }
  return out;
}

// B.12.1.3-5 exactly as printed: every grid point of the tile, one at a time.
std::vector<PacketId> brute_force(Order order, int layers, const Tile& t, const std::vector<ComponentGeometry>& comps) {
  std::vector<PacketId> out;
  auto body = [&](int c, int r, std::int64_t x, std::int64_t y) {
    const ComponentGeometry& comp = comps[static_cast<std::size_t>(c)];
    const int nl = static_cast<int>(comp.resolutions.size()) - 1;
    if (r > nl) return;
    const ResolutionGeometry& g = comp.resolutions[static_cast<std::size_t>(r)];
    const std::int64_t two_nl_r = std::int64_t{1} << (nl - r);
    const std::int64_t py = std::int64_t{1} << (g.ppy + nl - r), px = std::int64_t{1} << (g.ppx + nl - r);
    const bool ycond = y % (comp.dy * py) == 0 || (y == t.y0 && (g.y0 * two_nl_r) % py != 0);
    const bool xcond = x % (comp.dx * px) == 0 || (x == t.x0 && (g.x0 * two_nl_r) % px != 0);
    if (!ycond || !xcond) return;
    // (B-20)
    const std::int64_t k =
        ceil_div(x, comp.dx * two_nl_r) / (std::int64_t{1} << g.ppx) - g.x0 / (std::int64_t{1} << g.ppx) +
        g.precincts_wide *
            (ceil_div(y, comp.dy * two_nl_r) / (std::int64_t{1} << g.ppy) - g.y0 / (std::int64_t{1} << g.ppy));
    if (k < 0 || k >= count(comp, r)) return;  // "the next precinct, if one exists"
    for (int l = 0; l < layers; ++l) out.push_back({l, r, c, static_cast<int>(k)});
  };
  const int ncomp = static_cast<int>(comps.size());
  int max_nl = 0;
  for (const auto& c : comps) max_nl = std::max(max_nl, static_cast<int>(c.resolutions.size()) - 1);
  auto nl_of = [&](int c) { return static_cast<int>(comps[static_cast<std::size_t>(c)].resolutions.size()) - 1; };
  switch (order) {
    case Order::RPCL:
      for (int r = 0; r <= max_nl; ++r)
        for (std::int64_t y = t.y0; y < t.y1; ++y)
          for (std::int64_t x = t.x0; x < t.x1; ++x)
            for (int c = 0; c < ncomp; ++c) body(c, r, x, y);
      break;
    case Order::PCRL:
      for (std::int64_t y = t.y0; y < t.y1; ++y)
        for (std::int64_t x = t.x0; x < t.x1; ++x)
          for (int c = 0; c < ncomp; ++c)
            for (int r = 0; r <= nl_of(c); ++r) body(c, r, x, y);
      break;
    case Order::CPRL:
      for (int c = 0; c < ncomp; ++c)
        for (std::int64_t y = t.y0; y < t.y1; ++y)
          for (std::int64_t x = t.x0; x < t.x1; ++x)
            for (int r = 0; r <= nl_of(c); ++r) body(c, r, x, y);
      break;
    default:
      break;
  }
  return out;
}

void check_all_orders(const Tile& t, const std::vector<CompSpec>& specs, int layers) {
  const auto comps = geometry(t, specs);
  std::size_t expected = 0;
  for (const auto& c : comps)
    for (int r = 0; r < static_cast<int>(c.resolutions.size()); ++r)
      expected += static_cast<std::size_t>(layers) * static_cast<std::size_t>(count(c, r));
  for (Order o : {Order::LRCP, Order::RLCP, Order::RPCL, Order::PCRL, Order::CPRL}) {
    SCOPED_TRACE("order " + std::to_string(static_cast<int>(o)));
    const auto got = codec::t2::progression(o, layers, t.x0, t.y0, t.x1, t.y1, comps);
    // Exactly once each.
    std::set<std::tuple<int, int, int, int>> seen;
    for (const PacketId& p : got) {
      ASSERT_GE(p.layer, 0);
      ASSERT_LT(p.layer, layers);
      ASSERT_LT(p.resolution, static_cast<int>(comps[static_cast<std::size_t>(p.component)].resolutions.size()));
      ASSERT_GE(p.precinct, 0);
      ASSERT_LT(p.precinct, count(comps[static_cast<std::size_t>(p.component)], p.resolution));
      seen.insert({p.layer, p.resolution, p.component, p.precinct});
    }
    ASSERT_EQ(seen.size(), got.size()) << "duplicates";
    ASSERT_EQ(got.size(), expected);
    if (o == Order::LRCP || o == Order::RLCP)
      EXPECT_EQ(got, nested_lrcp_or_rlcp(o == Order::LRCP, layers, comps));
    else
      EXPECT_EQ(got, brute_force(o, layers, t, comps));
  }
}

// Three components with different level counts and sampling, an odd tile origin and precinct
// sizes that change from resolution to resolution (some origins fall inside precincts).
const std::vector<CompSpec> kMixed = {
    {1, 1, {{2, 2}, {2, 3}, {3, 2}, {4, 3}}},  // NL = 3
    {2, 2, {{1, 2}, {3, 3}, {2, 2}}},          // NL = 2, XRsiz = YRsiz = 2
    {1, 2, {{3, 1}, {2, 4}}},                  // NL = 1, YRsiz = 2
};

TEST(Progression, MixedComponentsOddOrigin) { check_all_orders({13, 7, 110, 83}, kMixed, 2); }
TEST(Progression, MixedComponentsZeroOrigin) { check_all_orders({0, 0, 64, 48}, kMixed, 3); }
TEST(Progression, MixedComponentsInteriorTile) { check_all_orders({37, 101, 91, 130}, kMixed, 1); }

TEST(Progression, OnePrecinctPerResolution) {
  const std::vector<CompSpec> big = {
      {1, 1, {{15, 15}, {15, 15}, {15, 15}, {15, 15}}},
      {2, 1, {{15, 15}, {15, 15}, {15, 15}}},
      {1, 1, {{15, 15}, {15, 15}}},
  };
  check_all_orders({13, 7, 110, 83}, big, 2);
  check_all_orders({0, 0, 50, 40}, big, 2);
  // One precinct per (component, resolution), so LRCP ... CPRL each just interleave those.
  const auto comps = geometry({13, 7, 110, 83}, big);
  const auto rpcl = codec::t2::progression(Order::RPCL, 1, 13, 7, 110, 83, comps);
  std::vector<PacketId> expect;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 3; ++c)
      if (r < static_cast<int>(comps[static_cast<std::size_t>(c)].resolutions.size())) expect.push_back({0, r, c, 0});
  EXPECT_EQ(rpcl, expect);
}

// XRsiz = 3 makes precinct sizes that are not multiples of one another on the reference grid.
TEST(Progression, NonPowerOfTwoSampling) {
  const std::vector<CompSpec> specs = {
      {3, 1, {{1, 1}, {2, 2}, {2, 3}}},
      {1, 3, {{2, 2}, {3, 2}}},
      {2, 2, {{2, 1}, {1, 2}, {2, 2}}},
  };
  check_all_orders({5, 11, 101, 77}, specs, 2);
}

// A narrow tile whose coarse resolutions are empty (no precincts, no packets).
TEST(Progression, EmptyResolutions) {
  const std::vector<CompSpec> specs = {
      {1, 1, {{1, 1}, {1, 1}, {1, 1}, {1, 1}}},
      {2, 2, {{2, 2}, {2, 2}}},
  };
  const auto comps = geometry({5, 5, 6, 40}, specs);
  EXPECT_EQ(count(comps[0], 0), 0);
  check_all_orders({5, 5, 6, 40}, specs, 2);
}

TEST(Progression, RejectsGeometryFromAnotherTile) {
  auto comps = geometry({13, 7, 110, 83}, kMixed);
  comps[0].resolutions[3].precincts_wide += 2;
  EXPECT_THROW(codec::t2::progression(Order::RPCL, 1, 13, 7, 110, 83, comps), std::invalid_argument);
  comps = geometry({13, 7, 110, 83}, kMixed);
  comps[1].dx = 0;
  EXPECT_THROW(codec::t2::progression(Order::LRCP, 1, 13, 7, 110, 83, comps), std::invalid_argument);
}

}  // namespace
