#include "codec/ht/ht_block_decoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <vector>

#include "bit_readers.h"
#include "block_geometry.h"
#include "codec/ht/cxt_vlc_table.h"
#include "simd_dispatch/scalar_clones.h"

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

// U-VLC (T.814 7.3.6): the prefix "1", "01", "001", "000" (first bit first) selects u = 1, 2,
// 3 + a 1-bit suffix, or 5 + a 5-bit suffix, which from 28 on is followed by a 4-bit extension
// (u = 5 + suffix + 4 extension).
enum class UvlcPrefix { One, Two, ThreeOrFour, FiveOrMore };

UvlcPrefix read_prefix(VlcReader& vlc) {
  const std::uint32_t bits = vlc.peek7();  // the first bit read in bit 0
  if (bits & 1) {
    vlc.skip(1);
    return UvlcPrefix::One;
  }
  if (bits & 2) {
    vlc.skip(2);
    return UvlcPrefix::Two;
  }
  vlc.skip(3);
  return (bits & 4) ? UvlcPrefix::ThreeOrFour : UvlcPrefix::FiveOrMore;
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

// ---- The cleanup pass (T.814 7.3) -----------------------------------------------------------------

// The widest row of quads a code-block has (1024 samples, T.800's limit).
constexpr int kMaxQuadsWide = 512;

// What one row of quads leaves for the next (and what the row being decoded has so far): each
// quad's significance pattern rho, restricted to the samples inside the block, at [qx + 1], and
// each sample column's exponent E (T.814 7.3.7: the bit length of 2 mu - 1, 0 for an insignificant
// sample) of the quad row's bottom sample, at [x + 1]. The entries either side stay 0: a quad or
// sample beyond the block's edge is insignificant. Every entry inside is written in every row.
struct QuadRow {
  std::array<std::uint8_t, kMaxQuadsWide + 2> rho{};
  std::array<std::uint8_t, 2 * kMaxQuadsWide + 4> bottom_exponent{};
};

// rho's bits of the samples of a row of quads inside the block: bits 1 and 3 are the bottom row; a
// quad whose right column is outside (the last of an odd width) keeps bits 0 and 1 alone.
constexpr std::uint8_t row_inside_mask(bool bottom_inside) { return bottom_inside ? 0xF : 0x5; }
constexpr std::uint8_t kLeftColumn = 0x3;

// Context c_q (T.814 7.3.5), as the encoder forms it: in the first row of quads from the four
// samples to the quad's left (the quad before it, `left`); elsewhere from the row above (x0 - 1 ..
// x0 + 2: the bottom samples of the quads above-left, above and above-right; north in bit 0, east
// in bit 2, RowAbove) and the two samples to its left (west, bit 1).
int first_row_context(std::uint8_t left) {
  return ((left | (left >> 1)) & 1) | (((left >> 2) & 1) << 1) | (((left >> 3) & 1) << 2);
}
int quad_context(std::uint8_t from_above, std::uint8_t left) {
  return from_above | ((((left >> 2) | (left >> 3)) & 1) << 1);
}

// What each quad of a row (not the first) takes from the row above, for all of them in one short
// loop before the row's VLC decoding, whose dependent chain it leaves shorter: its context's north
// and east bits, and the largest exponent of the four samples above it (x0 - 1 .. x0 + 2), from
// which kappa_q comes.
struct RowAbove {
  std::array<std::uint8_t, kMaxQuadsWide> context;
  std::array<std::uint8_t, kMaxQuadsWide> largest_exponent;
  void take(const QuadRow& above, int quads_wide) {
    for (int q = 0; q < quads_wide; ++q) {
      const auto at = static_cast<std::size_t>(q);
      const std::uint8_t left = above.rho[at], middle = above.rho[at + 1], right = above.rho[at + 2];
      context[at] =
          static_cast<std::uint8_t>((((left >> 3) | (middle >> 1)) & 1) | ((((middle >> 3) | (right >> 1)) & 1) << 2));
      const std::uint8_t* e = &above.bottom_exponent[2 * at];
      largest_exponent[at] = std::max(std::max(e[0], e[1]), std::max(e[2], e[3]));
    }
  }
};

// Exponent predictor kappa_q (T.814 7.3.7): 1 in the first row of quads and for a quad with at
// most one significant sample; otherwise the largest exponent of the four samples above it less
// one, at least 1.
int exponent_predictor(int largest_above, bool first_row, int rho) {
  if (first_row || (rho & (rho - 1)) == 0) return 1;
  return std::max(1, largest_above - 1);
}

// What stopped a malformed cleanup pass, for decode_ht_block to throw: the cleanup decoder itself
// does not throw, because GCC's x86-64-v3 clone of it (target_clones) ended the program at a throw
// (std::terminate) instead of unwinding.
struct CleanupFault {
  enum class Kind { None, Codeword, Exponent, Magnitude } kind = Kind::None;
  int exponent = 0;  // U_q, for Kind::Exponent
};

// Reads one quad's significance: a MEL symbol in context 0 (T.814 7.3.4), then, unless the MEL
// said the quad is empty, its CxtVLC codeword (a zero entry where it did). False where the bits
// start no codeword of the table.
bool read_quad(const VlcDecodingTable& table, VlcReader& vlc, MelDecoder& mel, int context, VlcEntry& code) {
  code = VlcEntry{};
  if (context == 0 && !mel.decode()) return true;
  code = table.lookup(context, vlc.peek7());
  vlc.skip(code.length);
  return code.length != 0;
}

[[noreturn]] void magnitude_too_large(const char* pass) {
  throw HtDecodeError(std::string("HT ") + pass + ": a magnitude beyond " + std::to_string(kHtMaxMagnitudeBits) +
                      " bits");
}

// MagSgn bits of a quad (T.814 7.3.8) whose top-left sample is out[0]: each significant sample's
// v_n = 2 (mu - 1) + sign in U_q bits, less its top bit where e_k implies it (its value is then
// e_1's bit). Writes the quad's samples as the header says, sign times (2 mu + 1) << p =
// ((v_n less its sign bit) + 3) << p, and 0 for the insignificant ones, and the bottom samples'
// exponents E = bit length of 2 mu - 1 = that of v_n with its sign bit set.
//
// read_whole_quad is the path of most quads: wholly inside the block, U_q + p within
// kHtMaxMagnitudeBits (no sample can overflow) and its bits covered by one ensure() of the MagSgn
// stream. It has no branch on rho, whose bits a lossless block's quads mix too often for a branch to
// be predicted (on the 2048x2048 mosaic a third of the decoder's mispredictions): an insignificant
// sample takes 0 bits, reads v = 0 and writes 0.
void read_whole_quad(const VlcEntry& code, int exponent_bits, int plane, MagSgnReader& magsgn, std::int32_t* out,
                     std::size_t stride, std::uint8_t* bottom) {
  const std::size_t position[4] = {0, stride, 1, stride + 1};
  const unsigned implied_ones = code.e_k & code.e_1;  // the top bits e_k implies that are 1
#pragma GCC unroll 4
  for (int n = 0; n < 4; ++n) {
    const unsigned significant = (code.rho >> n) & 1u;
    const int bits = (exponent_bits - ((code.e_k >> n) & 1)) & -static_cast<int>(significant);
    const std::uint64_t v =
        magsgn.take(bits) | (static_cast<std::uint64_t>((implied_ones >> n) & significant) << (exponent_bits - 1));
    const std::uint64_t doubled = (((v & ~std::uint64_t{1}) + 3) << plane) & -std::uint64_t{significant};
    const auto negative = -static_cast<std::int32_t>(v & 1);  // all ones for a negative sample
    out[position[n]] = (static_cast<std::int32_t>(doubled) ^ negative) - negative;
    if (n & 1) bottom[n >> 1] = static_cast<std::uint8_t>(std::bit_width(v | significant));
  }
}

// Any other quad, sample by sample: only the samples inside the block (`inside`: rho's bit
// positions of those) are written, and each magnitude is checked against the caller's 31 bits.
// False where one overflows.
bool read_quad_magnitudes(const VlcEntry& code, int exponent_bits, int plane, std::uint8_t inside, MagSgnReader& magsgn,
                          std::int32_t* out, std::size_t stride, std::uint8_t* bottom) {
  const std::size_t position[4] = {0, stride, 1, stride + 1};
  const unsigned implied_ones = code.e_k & code.e_1;
#pragma GCC unroll 4
  for (int n = 0; n < 4; ++n) {
    const bool in_block = (inside >> n) & 1;
    if (!((code.rho >> n) & 1)) {
      if (in_block) out[position[n]] = 0;
      continue;
    }
    const std::uint64_t v = magsgn.get(exponent_bits - ((code.e_k >> n) & 1)) |
                            (static_cast<std::uint64_t>((implied_ones >> n) & 1) << (exponent_bits - 1));
    const std::uint64_t doubled = ((v & ~std::uint64_t{1}) + 3) << plane;
    if (doubled >= (std::uint64_t{1} << (kHtMaxMagnitudeBits + 1))) return false;
    if (!in_block) continue;
    const auto negative = -static_cast<std::int32_t>(v & 1);
    out[position[n]] = (static_cast<std::int32_t>(doubled) ^ negative) - negative;
    if (n & 1) bottom[n >> 1] = static_cast<std::uint8_t>(std::bit_width(v | 1));
  }
  return true;
}

// An insignificant quad's samples inside the block (`inside` as above): 0.
void clear_quad(std::uint8_t inside, std::int32_t* out, std::size_t stride) {
  if (inside & 1) out[0] = 0;
  if (inside & 2) out[stride] = 0;
  if (inside & 4) out[1] = 0;
  if (inside & 8) out[stride + 1] = 0;
}

// The residuals u of a pair of quads (T.814 7.3.6; the first row's MEL rule is
// read_first_row_residuals'), for which of the two have one (`with`: bit 0 the first quad, bit 1
// the second, at least one): both prefixes, read together from one look at the next 6 VLC bits
// through this table, then both suffixes, then both extensions.
struct ResidualPrefixes {
  std::uint8_t length = 0;               // the prefixes' bits
  std::uint8_t suffix_bits[2] = {0, 0};  // 0, 1 or 5 for each quad (0 for a quad without one)
  std::uint8_t base[2] = {0, 0};         // u before the suffix: 1, 2, 3 or 5 (0 without one)
};

class ResidualTable {
 public:
  ResidualTable() {
    for (unsigned with = 1; with < 4; ++with)
      for (unsigned bits = 0; bits < 64; ++bits) {
        ResidualPrefixes& e = entries_[with * 64 + bits];
        unsigned rest = bits;
        for (int k = 0; k < 2; ++k) {
          if (!((with >> k) & 1)) continue;
          // "1", "01", "001", "000", first bit first (T.814 Table 3).
          const int length = (rest & 1) ? 1 : (rest & 2) ? 2 : 3;
          const int kind = (rest & 1) ? 0 : (rest & 2) ? 1 : (rest & 4) ? 2 : 3;
          static constexpr std::uint8_t kBase[4] = {1, 2, 3, 5}, kSuffix[4] = {0, 0, 1, 5};
          e.base[k] = kBase[kind];
          e.suffix_bits[k] = kSuffix[kind];
          e.length = static_cast<std::uint8_t>(e.length + length);
          rest >>= length;
        }
      }
  }
  const ResidualPrefixes& at(unsigned with, std::uint32_t bits6) const { return entries_[with * 64 + bits6]; }

 private:
  std::array<ResidualPrefixes, 4 * 64> entries_{};
};

const ResidualTable& residual_table() {
  static const ResidualTable table;
  return table;
}

void read_residuals(VlcReader& vlc, unsigned with, std::array<int, 2>& u) {
  const ResidualPrefixes& e = residual_table().at(with, vlc.peek7() & 0x3F);
  vlc.skip(e.length);
  const int s0 = e.suffix_bits[0];
  const std::uint32_t suffixes = vlc.get(s0 + e.suffix_bits[1]);
  u[0] = e.base[0] + static_cast<int>(suffixes & ((1u << s0) - 1));
  u[1] = e.base[1] + static_cast<int>(suffixes >> s0);
  // From 5 + 28 on, a 4-bit extension adds 4 times its value, the first quad's first.
  for (int k = 0; k < 2; ++k)
    if (e.suffix_bits[k] == 5 && u[static_cast<std::size_t>(k)] >= 5 + 28)
      u[static_cast<std::size_t>(k)] += 4 * static_cast<int>(vlc.get(4));
}

// The residuals of the first row's pair (T.814 7.3.6): where both quads have one, a MEL symbol
// first. After a 1 both are coded as elsewhere (read_residuals), each less 2; after a 0, the first
// quad's prefix comes first, and a first residual above 2 is then followed by a single bit giving
// the second (1 or 2), else by the second's prefix, and then the suffixes and extensions in order.
void read_first_row_residuals(VlcReader& vlc, MelDecoder& mel, unsigned with, std::array<int, 2>& u) {
  if (with == 0) return;
  if (with != 3 || mel.decode()) {
    read_residuals(vlc, with, u);
    if (with == 3) u = {u[0] + 2, u[1] + 2};
    return;
  }
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
}

// One quad of a row as the cleanup's first phase leaves it for the second: its significance
// pattern (all of it: every sample it names has MagSgn bits, inside the block or not), the EMB
// patterns, U_q, and which of its samples lie inside the block.
struct RowQuad {
  VlcEntry code;
  int exponent_bits = 0;
  std::uint8_t inside = 0;
};

// The largest U_q whose quad's MagSgn bits (four samples' at most) one ensure() covers.
constexpr int kOneReadExponent = 14;

// The cleanup pass over the whole block: writes every sample of `out` unless it finds a fault. Each
// row of quads in two phases: the significance and exponents of all its quads (MEL, CxtVLC and
// U-VLC: the VLC stream), then their magnitudes and signs (the MagSgn stream), which need the row
// above's exponents but nothing of their own row's. Built for x86-64-v3 as well
// (simd_dispatch/scalar_clones.h), everything inlined into it.
[[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]] CleanupFault decode_cleanup(std::span<const std::uint8_t> segment,
                                                                      std::size_t pcup, int plane, int width,
                                                                      int height, std::int32_t* out) {
  MagSgnReader magsgn(segment.first(pcup));
  MelDecoder mel(segment.subspan(pcup));
  VlcReader vlc(segment.subspan(pcup));
  // The row of quads above (all 0 for the first) and the one being decoded, swapped after each row.
  QuadRow rows[2];
  QuadRow* above_row = &rows[0];
  QuadRow* this_row = &rows[1];
  std::array<RowQuad, kMaxQuadsWide> quads;
  RowAbove from_above;
  const int quads_wide = (width + 1) / 2, quads_high = (height + 1) / 2;
  const auto stride = static_cast<std::size_t>(width);
  for (int qy = 0; qy < quads_high; ++qy) {
    const bool first_row = qy == 0;
    const std::uint8_t row_inside = row_inside_mask(2 * qy + 1 < height);
    const VlcDecodingTable& table = vlc_decoding_table(first_row ? QuadRowKind::Initial : QuadRowKind::Other);
    const QuadRow& above = *above_row;
    QuadRow& row = *this_row;
    if (!first_row) from_above.take(above, quads_wide);
    // Phase 1. Quads in pairs (T.814 7.3.1): both quads' significance, then their residuals.
    for (int qx = 0; qx < quads_wide; qx += 2) {
      const int count = std::min(2, quads_wide - qx);
      RowQuad* pair = &quads[static_cast<std::size_t>(qx)];
      unsigned with = 0;  // which of the pair have a U-VLC residual: bit 0 the first, bit 1 the second
      for (int k = 0; k < count; ++k) {
        const auto at = static_cast<std::size_t>(qx + k + 1);
        const int context =
            first_row ? first_row_context(row.rho[at - 1]) : quad_context(from_above.context[at - 1], row.rho[at - 1]);
        if (!read_quad(table, vlc, mel, context, pair[k].code)) return CleanupFault{CleanupFault::Kind::Codeword};
        pair[k].inside = row_inside;
        // Significance now: the next quad's context depends on it.
        row.rho[at] = pair[k].code.rho & row_inside;
        with |= static_cast<unsigned>(pair[k].code.u_off != 0) << k;
      }
      if (2 * (qx + count) > width) {  // the last quad of an odd width: its right column is outside
        pair[count - 1].inside &= kLeftColumn;
        row.rho[static_cast<std::size_t>(qx + count)] &= kLeftColumn;
      }
      std::array<int, 2> u{};
      if (first_row)
        read_first_row_residuals(vlc, mel, with, u);
      else if (with != 0)
        read_residuals(vlc, with, u);
      for (int k = 0; k < count; ++k) {
        RowQuad& q = pair[k];
        if (q.code.rho == 0) continue;
        q.exponent_bits =
            exponent_predictor(from_above.largest_exponent[static_cast<std::size_t>(qx + k)], first_row, q.code.rho) +
            u[static_cast<std::size_t>(k)];
        if (q.exponent_bits > 32) return CleanupFault{CleanupFault::Kind::Exponent, q.exponent_bits};
      }
    }
    // Phase 2: the row's magnitudes and signs, and its bottom samples' exponents for the next row.
    std::int32_t* row_out = out + static_cast<std::size_t>(2 * qy) * stride;
    for (int qx = 0; qx < quads_wide; ++qx) {
      const RowQuad& q = quads[static_cast<std::size_t>(qx)];
      const int x0 = 2 * qx;
      std::uint8_t* bottom = &row.bottom_exponent[static_cast<std::size_t>(x0) + 1];
      bottom[0] = bottom[1] = 0;
      if (q.code.rho == 0) {
        clear_quad(q.inside, row_out + x0, stride);
        continue;
      }
      // v < 2^U_q, so (2 mu + 1) << p <= (2^U_q + 1) << p, below 2^31 where U_q + p <= 30; four
      // samples of U_q <= 14 bits are at most one ensure() of the MagSgn stream.
      if (q.inside == 0xF && q.exponent_bits + plane <= kHtMaxMagnitudeBits && q.exponent_bits <= kOneReadExponent) {
        magsgn.ensure(4 * q.exponent_bits);
        read_whole_quad(q.code, q.exponent_bits, plane, magsgn, row_out + x0, stride, bottom);
      } else if (!read_quad_magnitudes(q.code, q.exponent_bits, plane, q.inside, magsgn, row_out + x0, stride,
                                       bottom)) {
        return CleanupFault{CleanupFault::Kind::Magnitude};
      }
    }
    std::swap(above_row, this_row);
  }
  return {};
}

// ---- The refinement passes (T.814 7.4, 7.5) on plane p - 1 ---------------------------------------

// Both passes visit samples in the order of T.800's passes: stripes of four rows, column by column
// within a stripe, top to bottom within a column; SigProp in groups of four columns (below). Each
// sample's state is a byte of a grid with a border of one sample all round (so that neighbours need
// no bounds test): bit 0 significant after the cleanup, bit 1 found significant by SigProp.
constexpr std::uint8_t kCleanupSignificant = 1, kFoundSignificant = 2;

class RefinementGrid {
 public:
  RefinementGrid(std::span<const std::int32_t> cleanup, int width, int height)
      : width_(width), height_(height), stride_(static_cast<std::size_t>(width) + 2) {
    state_.assign(stride_ * (static_cast<std::size_t>(height) + 2), 0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        state_[at(x, y)] =
            cleanup[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] != 0
                ? kCleanupSignificant
                : 0;
  }

  // SigProp (T.814 7.4): an insignificant sample with a significant neighbour among its eight gets
  // one bit, 1 making it significant at plane p - 1. As in T.800's significance propagation pass,
  // neighbours visited before it count with what this pass found, later ones with what the cleanup
  // found (they have found nothing yet), and with vertically causal coding (0x08) the stripe below
  // does not count. The bits come in groups of four columns of a stripe: the significance bits of
  // the group's samples in visiting order, then one sign bit (1: negative) for each sample that
  // became significant, in that order. Returns those samples, each with its sign.
  void sig_prop(SigPropReader& bits, bool vertically_causal, std::vector<std::pair<std::size_t, bool>>& found) {
    found.clear();
    for (int y0 = 0; y0 < height_; y0 += 4) {
      const int y1 = std::min(y0 + 4, height_);
      for (int x0 = 0; x0 < width_; x0 += 4) {
        const std::size_t group = found.size();
        for (int x = x0; x < std::min(x0 + 4, width_); ++x)
          for (int y = y0; y < y1; ++y) {
            const std::size_t i = at(x, y);
            if (state_[i] != 0) continue;  // significant already (SigProp never revisits a sample)
            const bool below_counts = !(vertically_causal && y == y0 + 3);
            const std::uint8_t* up = &state_[i - stride_];
            const std::uint8_t* down = &state_[i + stride_];
            const int neighbours = up[-1] | up[0] | up[1] | state_[i - 1] | state_[i + 1] |
                                   (below_counts ? down[-1] | down[0] | down[1] : 0);
            if (neighbours == 0) continue;
            if (bits.bit()) {
              state_[i] = kFoundSignificant;
              found.emplace_back(index(x, y), false);
            }
          }
        for (std::size_t k = group; k < found.size(); ++k) found[k].second = bits.bit() != 0;
      }
    }
  }

  // MagRef (T.814 7.5): every sample significant after the cleanup pass gets its bit at plane p - 1,
  // in visiting order: the sample's magnitude moves by half of the cleanup's interval, up for a 1.
  void mag_ref(MagRefReader& bits, int plane, std::span<std::int32_t> out) {
    const std::int64_t half = std::int64_t{1} << plane;
    for (int y0 = 0; y0 < height_; y0 += 4)
      for (int x = 0; x < width_; ++x)
        for (int y = y0; y < std::min(y0 + 4, height_); ++y) {
          if (state_[at(x, y)] != kCleanupSignificant) continue;
          std::int32_t& v = out[index(x, y)];
          const std::int64_t magnitude = (v < 0 ? -static_cast<std::int64_t>(v) : v) + (bits.bit() ? half : -half);
          if (magnitude >= (std::int64_t{1} << (kHtMaxMagnitudeBits + 1))) magnitude_too_large("refinement");
          v = static_cast<std::int32_t>(v < 0 ? -magnitude : magnitude);
        }
  }

 private:
  std::size_t at(int x, int y) const {
    return (static_cast<std::size_t>(y) + 1) * stride_ + static_cast<std::size_t>(x) + 1;
  }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  int width_, height_;
  std::size_t stride_;
  std::vector<std::uint8_t> state_;
};

// The SigProp and MagRef passes after the cleanup, on the cleanup's samples in `out` (see the
// header for what they leave).
void refine(const HtCodewords& block, int width, int height, std::span<std::int32_t> out) {
  if (block.cleanup_plane < 1)
    throw HtDecodeError("HT refinement passes after a cleanup pass on bit-plane 0 (there is no plane below it)");
  const int plane = block.cleanup_plane - 1;
  RefinementGrid grid(out, width, height);
  SigPropReader sig_prop_bits(block.refinement);
  std::vector<std::pair<std::size_t, bool>> found;
  grid.sig_prop(sig_prop_bits, block.vertically_causal, found);
  if (block.refinement_passes >= 2) {
    MagRefReader mag_ref_bits(block.refinement);
    grid.mag_ref(mag_ref_bits, plane, out);
  }
  // Found by SigProp: rebuilt at 1.5 times plane p - 1's step.
  const auto found_magnitude = static_cast<std::int32_t>(3) << plane;
  for (const auto& [i, negative] : found) out[i] = negative ? -found_magnitude : found_magnitude;
}

}  // namespace

void decode_ht_block(const HtCodewords& block, int width, int height, std::span<std::int32_t> out) {
  check_size(width, height);
  const auto samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (out.size() != samples) throw std::invalid_argument("HT block: the output must hold width * height samples");
  const std::span<const std::uint8_t> d = block.cleanup;
  if (d.empty()) return std::fill(out.begin(), out.end(), 0);
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
  const CleanupFault fault = decode_cleanup(d, d.size() - scup, block.cleanup_plane, width, height, out.data());
  switch (fault.kind) {
    case CleanupFault::Kind::None:
      break;
    case CleanupFault::Kind::Codeword:
      throw HtDecodeError("HT cleanup: a CxtVLC codeword that no table row has");
    case CleanupFault::Kind::Exponent:
      throw HtDecodeError("HT cleanup: a quad exponent U_q of " + std::to_string(fault.exponent));
    case CleanupFault::Kind::Magnitude:
      magnitude_too_large("cleanup");
  }
  if (block.refinement_passes > 0) refine(block, width, height, out);
}

}  // namespace codec::ht
