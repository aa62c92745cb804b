#include "codec/ht/ht_block_decoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <vector>

#include "bit_readers.h"
#include "block_geometry.h"
#include "codec/ht/cxt_vlc_table.h"

namespace codec::ht {
namespace {

// The decoder's view of a CxtVLC table (T.814 Annex C, the rows of cxt_vlc_table.cpp): for a quad
// context and the next 7 VLC bits, the row whose codeword those bits start with. Each context's
// codewords form a prefix code (ht_block_test checks their Kraft sums), so a row fills every 7-bit
// pattern that extends its codeword.
struct VlcEntry {
  std::uint8_t length = 0;  // 0: no codeword starts so (a malformed stream)
  std::uint8_t rho = 0, u_off = 0, e_k = 0, e_1 = 0;
};

class VlcDecodingTable {
 public:
  explicit VlcDecodingTable(QuadRowKind kind) {
    for (const CxtVlcRow& row : cxt_vlc_rows(kind))
      for (unsigned high = 0; high < (1u << (7 - row.length)); ++high)
        entries_[static_cast<std::size_t>(row.context) * 128 + ((high << row.length) | row.codeword)] =
            VlcEntry{row.length, row.rho, row.u_off, row.e_k, row.e_1};
  }
  const VlcEntry& lookup(int context, std::uint32_t bits7) const {
    return entries_[static_cast<std::size_t>(context) * 128 + bits7];
  }

 private:
  std::array<VlcEntry, 8 * 128> entries_{};
};

const VlcDecodingTable& vlc_decoding_table(QuadRowKind kind) {
  static const VlcDecodingTable initial(QuadRowKind::Initial), other(QuadRowKind::Other);
  return kind == QuadRowKind::Initial ? initial : other;
}

// What the cleanup pass knows of the block so far: significance (known from each quad's rho as soon
// as its codeword is read, before its magnitudes) and the decoded magnitudes and signs.
class DecodedGrid {
 public:
  DecodedGrid(int width, int height)
      : width_(width),
        height_(height),
        mu_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0),
        negative_(mu_.size(), 0),
        significant_(mu_.size(), 0) {}
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  int significant(int x, int y) const { return inside(x, y) ? significant_[index(x, y)] : 0; }
  // E_n = bit length of 2 mu - 1 (T.814 7.3.7), 0 for an insignificant sample.
  int exponent(int x, int y) const {
    if (!inside(x, y)) return 0;
    const std::uint32_t mu = mu_[index(x, y)];
    return mu == 0 ? 0 : static_cast<int>(std::bit_width(2 * static_cast<std::uint64_t>(mu) - 1));
  }
  void mark_significant(int x, int y) {
    if (inside(x, y)) significant_[index(x, y)] = 1;
  }
  void set(int x, int y, std::uint32_t mu, bool negative) {
    if (!inside(x, y)) return;
    mu_[index(x, y)] = mu;
    negative_[index(x, y)] = negative ? 1 : 0;
  }
  std::uint32_t mu(std::size_t i) const { return mu_[i]; }
  bool negative(std::size_t i) const { return negative_[i] != 0; }
  bool significant_after_cleanup(int x, int y) const { return inside(x, y) && mu_[index(x, y)] != 0; }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  int width_, height_;
  std::vector<std::uint32_t> mu_;
  std::vector<std::uint8_t> negative_, significant_;
};

// Context c_q (T.814 7.3.5), as the encoder forms it: in the first row of quads from the four
// samples to the quad's left; elsewhere from the row above (x0 - 1 .. x0 + 2) and the two samples
// to its left.
int quad_context(const DecodedGrid& g, int x0, int y0) {
  if (y0 == 0) {
    const int far = g.significant(x0 - 2, 0) | g.significant(x0 - 2, 1);
    return far | (g.significant(x0 - 1, 0) << 1) | (g.significant(x0 - 1, 1) << 2);
  }
  const int north = g.significant(x0 - 1, y0 - 1) | g.significant(x0, y0 - 1);
  const int west = g.significant(x0 - 1, y0) | g.significant(x0 - 1, y0 + 1);
  const int east = g.significant(x0 + 1, y0 - 1) | g.significant(x0 + 2, y0 - 1);
  return north | (west << 1) | (east << 2);
}

// Exponent predictor kappa_q (T.814 7.3.7): 1 in the first row of quads and for a quad with at
// most one significant sample; otherwise the largest exponent of the four samples above it less
// one, at least 1.
int exponent_predictor(const DecodedGrid& g, int x0, int y0, int rho) {
  if (y0 == 0 || (rho & (rho - 1)) == 0) return 1;
  int largest = 0;
  for (int dx = -1; dx <= 2; ++dx) largest = std::max(largest, g.exponent(x0 + dx, y0 - 1));
  return std::max(1, largest - 1);
}

// U-VLC (T.814 7.3.6): the prefix "1", "01", "001", "000" (first bit first) selects u = 1, 2,
// 3 + a 1-bit suffix, or 5 + a 5-bit suffix, which from 28 on is followed by a 4-bit extension
// (u = 5 + suffix + 4 extension).
enum class UvlcPrefix { One, Two, ThreeOrFour, FiveOrMore };

UvlcPrefix read_prefix(VlcReader& vlc) {
  if (vlc.get(1)) return UvlcPrefix::One;
  if (vlc.get(1)) return UvlcPrefix::Two;
  if (vlc.get(1)) return UvlcPrefix::ThreeOrFour;
  return UvlcPrefix::FiveOrMore;
}

// The value a prefix and its suffix give, without the extension.
int prefix_value(UvlcPrefix prefix, std::uint32_t suffix) {
  switch (prefix) {
    case UvlcPrefix::One:
      return 1;
    case UvlcPrefix::Two:
      return 2;
    case UvlcPrefix::ThreeOrFour:
      return 3 + static_cast<int>(suffix);
    case UvlcPrefix::FiveOrMore:
      return 5 + static_cast<int>(suffix);
  }
  return 0;
}

int suffix_bits(UvlcPrefix prefix) {
  return prefix == UvlcPrefix::ThreeOrFour ? 1 : prefix == UvlcPrefix::FiveOrMore ? 5 : 0;
}

// Suffix and extension of one residual whose prefix was read.
int finish_uvlc(VlcReader& vlc, UvlcPrefix prefix, std::uint32_t suffix) {
  int u = prefix_value(prefix, suffix);
  if (prefix == UvlcPrefix::FiveOrMore && suffix >= 28) u += 4 * static_cast<int>(vlc.get(4));
  return u;
}

// The residuals of one or two quads (count), in the order the encoder writes them: both prefixes,
// both suffixes, both extensions; in the first row, a pair that both have residuals first takes a
// MEL symbol (T.814 7.3.6): 1 means both exceed 2 and are sent less 2; after a 0, a first residual
// above 2 is followed by a single bit giving the second (1 or 2).
void read_pair_residuals(VlcReader& vlc, MelDecoder& mel, const bool* has_residual, int count, bool initial_row,
                         std::array<int, 2>& u) {
  u = {0, 0};
  const bool both = count == 2 && has_residual[0] && has_residual[1];
  if (both && initial_row && !mel.decode()) {
    const UvlcPrefix first = read_prefix(vlc);
    if (first == UvlcPrefix::ThreeOrFour || first == UvlcPrefix::FiveOrMore) {
      u[1] = 1 + static_cast<int>(vlc.get(1));
      const std::uint32_t s = vlc.get(suffix_bits(first));
      u[0] = finish_uvlc(vlc, first, s);
      return;
    }
    const UvlcPrefix second = read_prefix(vlc);
    const std::uint32_t s0 = vlc.get(suffix_bits(first)), s1 = vlc.get(suffix_bits(second));
    u[0] = finish_uvlc(vlc, first, s0);
    u[1] = finish_uvlc(vlc, second, s1);
    return;
  }
  const int bonus = both && initial_row ? 2 : 0;  // reached only after a MEL 1 in the first row
  std::array<UvlcPrefix, 2> prefixes{};
  std::array<std::uint32_t, 2> suffixes{};
  std::array<int, 2> coded{};
  int n = 0;
  for (int k = 0; k < count; ++k)
    if (has_residual[k]) coded[static_cast<std::size_t>(n++)] = k;
  for (int i = 0; i < n; ++i) prefixes[static_cast<std::size_t>(i)] = read_prefix(vlc);
  for (int i = 0; i < n; ++i)
    suffixes[static_cast<std::size_t>(i)] = vlc.get(suffix_bits(prefixes[static_cast<std::size_t>(i)]));
  for (int i = 0; i < n; ++i)
    u[static_cast<std::size_t>(coded[static_cast<std::size_t>(i)])] =
        finish_uvlc(vlc, prefixes[static_cast<std::size_t>(i)], suffixes[static_cast<std::size_t>(i)]) + bonus;
}

struct QuadState {
  int x0 = 0, y0 = 0;
  VlcEntry code;
};

// Reads one quad's significance: a MEL symbol in context 0 (T.814 7.3.4), then, unless the MEL
// said the quad is empty, its CxtVLC codeword. Marks its significant samples at once: the next
// quad's context depends on them.
QuadState read_quad(DecodedGrid& g, const VlcDecodingTable& table, VlcReader& vlc, MelDecoder& mel, int x0, int y0) {
  QuadState q;
  q.x0 = x0;
  q.y0 = y0;
  const int context = quad_context(g, x0, y0);
  if (context == 0 && !mel.decode()) return q;
  q.code = table.lookup(context, vlc.peek7());
  if (q.code.length == 0) throw HtDecodeError("HT cleanup: a CxtVLC codeword that no table row has");
  vlc.skip(q.code.length);
  for (int n = 0; n < 4; ++n)
    if ((q.code.rho >> n) & 1) g.mark_significant(x0 + kQuadOffsets[n][0], y0 + kQuadOffsets[n][1]);
  return q;
}

// MagSgn bits of a quad (T.814 7.3.8): each significant sample's v_n = 2 (mu - 1) + sign in U_q
// bits, less its top bit where e_k implies it (its value is then e_1's bit).
void read_magnitudes(DecodedGrid& g, const QuadState& q, int exponent_bits, int plane, MagSgnReader& magsgn) {
  for (int n = 0; n < 4; ++n) {
    if (!((q.code.rho >> n) & 1)) continue;
    const int implied = (q.code.e_k >> n) & 1;
    std::uint64_t v = magsgn.get(exponent_bits - implied);
    if (implied) v |= static_cast<std::uint64_t>((q.code.e_1 >> n) & 1) << (exponent_bits - 1);
    const std::uint64_t mu = (v >> 1) + 1;
    // (2 mu + 1) << p must fit the caller's 31 bits.
    if (((2 * mu + 1) << plane) >= (std::uint64_t{1} << (kHtMaxMagnitudeBits + 1)))
      throw HtDecodeError("HT cleanup: a magnitude beyond " + std::to_string(kHtMaxMagnitudeBits) + " bits");
    g.set(q.x0 + kQuadOffsets[n][0], q.y0 + kQuadOffsets[n][1], static_cast<std::uint32_t>(mu), (v & 1) != 0);
  }
}

// ---- The refinement passes (T.814 7.4, 7.5) on plane p - 1 ---------------------------------------

// Both passes visit samples in the order of T.800's passes: stripes of four rows, column by column
// within a stripe, top to bottom within a column; SigProp in groups of four columns (below).
class RefinementDecoder {
 public:
  RefinementDecoder(const DecodedGrid& cleanup, int width, int height, bool vertically_causal)
      : cleanup_(cleanup),
        width_(width),
        height_(height),
        vertically_causal_(vertically_causal),
        became_significant_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0),
        negative_(became_significant_.size(), 0) {}

  // SigProp (T.814 7.4): an insignificant sample with a significant neighbour among its eight gets
  // one bit, 1 making it significant at plane p - 1. As in T.800's significance propagation pass,
  // neighbours visited before it count with what this pass found, later ones with what the cleanup
  // found, and with vertically causal coding (0x08) the stripe below does not count. The bits come in
  // groups of four columns of a stripe: the significance bits of the group's samples in visiting
  // order, then one sign bit (1: negative) for each sample that became significant, in that order.
  void sig_prop(SigPropReader& bits) {
    std::vector<std::size_t> found;
    for (int y0 = 0; y0 < height_; y0 += 4) {
      const int y1 = std::min(y0 + 4, height_);
      for (int x0 = 0; x0 < width_; x0 += 4) {
        found.clear();
        for (int x = x0; x < std::min(x0 + 4, width_); ++x)
          for (int y = y0; y < y1; ++y) {
            if (cleanup_.significant_after_cleanup(x, y) || !has_significant_neighbour(x, y, y0)) continue;
            if (bits.bit()) {
              became_significant_[index(x, y)] = 1;
              found.push_back(index(x, y));
            }
          }
        for (std::size_t i : found) negative_[i] = static_cast<std::uint8_t>(bits.bit());
      }
    }
  }

  // MagRef (T.814 7.5): every sample significant after the cleanup pass gets its bit at plane p - 1,
  // in visiting order.
  void mag_ref(MagRefReader& bits, std::vector<std::uint8_t>& refinement_bit) {
    for (int y0 = 0; y0 < height_; y0 += 4)
      for (int x = 0; x < width_; ++x)
        for (int y = y0; y < std::min(y0 + 4, height_); ++y)
          if (cleanup_.significant_after_cleanup(x, y))
            refinement_bit[index(x, y)] = static_cast<std::uint8_t>(bits.bit());
  }

  bool became_significant(std::size_t i) const { return became_significant_[i] != 0; }
  bool negative(std::size_t i) const { return negative_[i] != 0; }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  bool has_significant_neighbour(int x, int y, int stripe_top) const {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
        if (ny >= stripe_top + 4 && vertically_causal_) continue;
        if (cleanup_.significant_after_cleanup(nx, ny) || became_significant_[index(nx, ny)]) return true;
      }
    return false;
  }

  const DecodedGrid& cleanup_;
  int width_, height_;
  bool vertically_causal_;
  std::vector<std::uint8_t> became_significant_, negative_;
};

// The SigProp and MagRef passes after the cleanup, and the samples they leave (see the header).
void refine(const DecodedGrid& grid, const HtCodewords& block, int width, int height, std::span<std::int32_t> out) {
  if (block.cleanup_plane < 1)
    throw HtDecodeError("HT refinement passes after a cleanup pass on bit-plane 0 (there is no plane below it)");
  const int plane = block.cleanup_plane - 1;
  RefinementDecoder passes(grid, width, height, block.vertically_causal);
  SigPropReader sig_prop_bits(block.refinement);
  passes.sig_prop(sig_prop_bits);
  const bool mag_ref = block.refinement_passes >= 2;
  std::vector<std::uint8_t> refinement_bit;
  if (mag_ref) {
    refinement_bit.assign(out.size(), 0);
    MagRefReader mag_ref_bits(block.refinement);
    passes.mag_ref(mag_ref_bits, refinement_bit);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::uint64_t mu = grid.mu(i);
    std::uint64_t doubled = 0;  // twice the reconstructed magnitude
    bool negative = false;
    if (mu != 0) {
      doubled = mag_ref ? (2 * (2 * mu + refinement_bit[i]) + 1) << plane : (2 * mu + 1) << (plane + 1);
      negative = grid.negative(i);
    } else if (passes.became_significant(i)) {
      doubled = std::uint64_t{3} << plane;
      negative = passes.negative(i);
    }
    if (doubled >= (std::uint64_t{1} << (kHtMaxMagnitudeBits + 1)))
      throw HtDecodeError("HT refinement: a magnitude beyond " + std::to_string(kHtMaxMagnitudeBits) + " bits");
    out[i] = negative ? -static_cast<std::int32_t>(doubled) : static_cast<std::int32_t>(doubled);
  }
}

}  // namespace

void decode_ht_block(const HtCodewords& block, int width, int height, std::span<std::int32_t> out) {
  check_size(width, height);
  const auto samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (out.size() != samples) throw std::invalid_argument("HT block: the output must hold width * height samples");
  std::fill(out.begin(), out.end(), 0);
  const std::span<const std::uint8_t> d = block.cleanup;
  if (d.empty()) return;
  if (block.cleanup_plane < 0 || block.cleanup_plane >= kHtMaxMagnitudeBits)
    throw HtDecodeError("HT cleanup: bit-plane " + std::to_string(block.cleanup_plane) + " is beyond " +
                        std::to_string(kHtMaxMagnitudeBits - 1));
  // T.814 7.1: Scup, the MEL and VLC bytes' count, in the last byte and the low nibble of the one
  // before it; 2 <= Scup <= min(Lcup, 4079).
  if (d.size() < 2)
    throw HtDecodeError("HT cleanup: a segment of " + std::to_string(d.size()) + " byte(s) holds no Scup");
  const std::size_t scup = (static_cast<std::size_t>(d[d.size() - 1]) << 4) | (d[d.size() - 2] & 0x0F);
  if (scup < 2 || scup > d.size() || scup > 4079)
    throw HtDecodeError("HT cleanup: Scup " + std::to_string(scup) + " does not fit a segment of " +
                        std::to_string(d.size()) + " bytes");
  const std::size_t pcup = d.size() - scup;
  MagSgnReader magsgn(d.first(pcup));
  MelDecoder mel(d.subspan(pcup));
  VlcReader vlc(d.subspan(pcup));

  DecodedGrid grid(width, height);
  const int quads_wide = (width + 1) / 2, quads_high = (height + 1) / 2;
  for (int qy = 0; qy < quads_high; ++qy) {
    const bool initial_row = qy == 0;
    const VlcDecodingTable& table = vlc_decoding_table(initial_row ? QuadRowKind::Initial : QuadRowKind::Other);
    // Quads in pairs (T.814 7.3.1): both quads' significance, their residuals, then MagSgn.
    for (int qx = 0; qx < quads_wide; qx += 2) {
      const int count = std::min(2, quads_wide - qx);
      std::array<QuadState, 2> quads;
      bool has_residual[2] = {false, false};
      for (int k = 0; k < count; ++k) {
        quads[static_cast<std::size_t>(k)] = read_quad(grid, table, vlc, mel, 2 * (qx + k), 2 * qy);
        has_residual[k] = quads[static_cast<std::size_t>(k)].code.u_off != 0;
      }
      std::array<int, 2> u{};
      read_pair_residuals(vlc, mel, has_residual, count, initial_row, u);
      for (int k = 0; k < count; ++k) {
        const QuadState& q = quads[static_cast<std::size_t>(k)];
        if (q.code.rho == 0) continue;
        const int exponent_bits = exponent_predictor(grid, q.x0, q.y0, q.code.rho) + u[static_cast<std::size_t>(k)];
        if (exponent_bits > 32)
          throw HtDecodeError("HT cleanup: a quad exponent U_q of " + std::to_string(exponent_bits));
        read_magnitudes(grid, q, exponent_bits, block.cleanup_plane, magsgn);
      }
    }
  }
  if (block.refinement_passes <= 0) {
    for (std::size_t i = 0; i < samples; ++i) {
      const std::uint32_t mu = grid.mu(i);
      if (mu == 0) continue;
      const auto magnitude = static_cast<std::int32_t>((2 * mu + 1) << block.cleanup_plane);
      out[i] = grid.negative(i) ? -magnitude : magnitude;
    }
    return;
  }
  refine(grid, block, width, height, out);
}

}  // namespace codec::ht
