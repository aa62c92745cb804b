// The HT block coder against an independent model of T.814's cleanup decoding: a plain decoder
// written here from the standard's equations (the MEL run-length decoder, the VLC read backwards
// with its bit-unstuffing, CxtVLC decoding by searching the table's rows, U-VLC, the exponent
// predictor and MagSgn with the EMB's implied bits), which must recover every random block the
// encoder codes: the exact magnitudes and signs at cleanup plane 0, and |q| >> p with its sign at
// plane p. Every code-block shape, every bit-plane count. The same for the SigProp and MagRef
// refinement passes after a cleanup on plane p: a model of their raw streams (forwards and
// backwards in the refinement segment, each with its bit-stuffing) and of which samples SigProp
// visits recovers plane p - 1. The decoders in j2k_ht_test and j2k_ht_rate_test then prove the
// same through OpenJPEG, Grok and OpenJPH. Last, rate control's plane statistics (errors and
// counts for every cleanup plane, gathered in one SIMD visit) against their definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "codec/ht/cxt_vlc_table.h"
#include "codec/ht/ht_block_encoder.h"

namespace {

using codec::ht::CxtVlcRow;
using codec::ht::QuadRowKind;

// ---- The model decoder -------------------------------------------------------------------------

// MagSgn (T.814 7.1.2): forward, least significant bit first; a byte after 0xFF gives 7 bits; past
// the MagSgn part (Pcup bytes) the decoder reads 0xFF.
class MagSgnReader {
 public:
  MagSgnReader(const std::vector<std::uint8_t>& d, std::size_t pcup) : d_(d), pcup_(pcup) {}
  std::uint32_t read(int count) {
    std::uint32_t v = 0;
    for (int i = 0; i < count; ++i) v |= static_cast<std::uint32_t>(bit()) << i;
    return v;
  }

 private:
  int bit() {
    if (left_ == 0) {
      const unsigned byte = pos_ < pcup_ ? d_[pos_] : 0xFF;
      ++pos_;
      left_ = previous_ff_ ? 7 : 8;
      previous_ff_ = byte == 0xFF;
      current_ = byte;
      used_ = 0;
    }
    --left_;
    return static_cast<int>((current_ >> used_++) & 1);
  }
  const std::vector<std::uint8_t>& d_;
  std::size_t pcup_, pos_ = 0;
  int left_ = 0, used_ = 0;
  unsigned current_ = 0;
  bool previous_ff_ = false;
};

// The MEL bits (T.814 7.1.3): forward from Pcup, most significant bit first, 7 bits after 0xFF,
// 0xFF past the end. The run-length decoder (7.3.3) on top, with the 13-entry exponent table.
class MelDecoder {
 public:
  MelDecoder(const std::vector<std::uint8_t>& d, std::size_t pcup) : d_(d), pos_(pcup) {}
  int decode() {
    while (zeros_ == 0 && !one_) {
      if (bit()) {
        zeros_ = 1 << kE[k_];
        k_ = std::min(k_ + 1, 12);
      } else {
        int run = 0;
        for (int i = 0; i < kE[k_]; ++i) run = run << 1 | bit();
        zeros_ = run;
        one_ = true;
        k_ = std::max(k_ - 1, 0);
      }
    }
    if (zeros_ > 0) {
      --zeros_;
      return 0;
    }
    one_ = false;
    return 1;
  }

 private:
  int bit() {
    if (left_ == 0) {
      const unsigned byte = pos_ < d_.size() ? d_[pos_] : 0xFF;
      ++pos_;
      left_ = previous_ff_ ? 7 : 8;
      previous_ff_ = byte == 0xFF;
      current_ = byte;
    }
    --left_;
    return static_cast<int>((current_ >> left_) & 1);
  }
  static constexpr int kE[13] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 4, 5};
  const std::vector<std::uint8_t>& d_;
  std::size_t pos_;
  int left_ = 0;
  unsigned current_ = 0;
  bool previous_ff_ = false;
  int k_ = 0, zeros_ = 0;
  bool one_ = false;
};

// The VLC bits (T.814 7.1.4), unpacked up front: backwards from the segment's end, least
// significant bit first; the last byte is Scup's, the one before gives its upper 4 bits; a byte
// whose predecessor (in reading order) exceeds 0x8F and whose low 7 bits are all 1 gives 7 bits.
std::vector<int> vlc_bits(const std::vector<std::uint8_t>& d) {
  std::vector<int> bits;
  unsigned last = 0xFF;
  for (std::size_t i = d.size() - 1; i-- > 0;) {
    const unsigned byte = i == d.size() - 2 ? (d[i] | 0x0Fu) : d[i];
    const int first = i == d.size() - 2 ? 4 : 0;
    const int count = last > 0x8F && (byte & 0x7F) == 0x7F ? 7 : 8;
    for (int b = first; b < count; ++b) bits.push_back(static_cast<int>((byte >> b) & 1));
    last = d[i];
  }
  bits.resize(bits.size() + 64, 0);
  return bits;
}

struct Decoded {
  std::vector<std::uint32_t> mu;
  std::vector<int> negative;
  std::vector<char> read;  // SigProp: the samples it read a bit for
};

int exponent_of(std::uint32_t mu) {  // smallest E with 2 mu - 1 < 2^E
  if (mu == 0) return 0;
  int e = 0;
  while ((std::uint64_t{1} << e) <= 2 * std::uint64_t{mu} - 1) ++e;
  return e;
}

Decoded decode_cleanup(const std::vector<std::uint8_t>& d, int width, int height) {
  const std::size_t lcup = d.size();
  const std::size_t scup = 16u * d[lcup - 1] + (d[lcup - 2] & 0x0Fu);
  EXPECT_GE(scup, 2u);
  EXPECT_LE(scup, lcup);
  const std::size_t pcup = lcup - scup;
  MagSgnReader magsgn(d, pcup);
  MelDecoder mel(d, pcup);
  const std::vector<int> vlc = vlc_bits(d);
  std::size_t vpos = 0;
  auto vbit = [&] { return vlc.at(vpos++); };

  const int qw = (width + 1) / 2, qh = (height + 1) / 2;
  const int pw = 2 * qw, ph = 2 * qh;  // the quad grid, which may overhang the block
  std::vector<int> sigma(static_cast<std::size_t>(pw * ph), 0), expo(static_cast<std::size_t>(pw * ph), 0);
  std::vector<std::uint32_t> mu(static_cast<std::size_t>(pw * ph), 0);
  std::vector<int> neg(static_cast<std::size_t>(pw * ph), 0);
  auto at = [&](std::vector<int>& a, int x, int y) -> int {
    return x < 0 || y < 0 || x >= pw || y >= ph ? 0 : a[static_cast<std::size_t>(y * pw + x)];
  };
  const int dx[4] = {0, 0, 1, 1}, dy[4] = {0, 1, 0, 1};

  auto find_row = [&](QuadRowKind kind, int c) -> const CxtVlcRow& {
    for (const CxtVlcRow& r : codec::ht::cxt_vlc_rows(kind)) {
      if (r.context != c) continue;
      bool match = true;
      for (int i = 0; i < r.length && match; ++i)
        match = vlc.at(vpos + static_cast<std::size_t>(i)) == ((r.codeword >> i) & 1);
      if (match) {
        vpos += r.length;
        return r;
      }
    }
    ADD_FAILURE() << "no CxtVLC codeword matches";
    static const CxtVlcRow none{};
    return none;
  };
  auto u_prefix = [&] { return vbit() ? 1 : vbit() ? 2 : vbit() ? 3 : 5; };
  auto u_suffix = [&](int pfx) {
    if (pfx < 3) return 0;
    if (pfx == 3) return vbit();
    int v = 0;
    for (int i = 0; i < 5; ++i) v |= vbit() << i;
    return v;
  };
  auto u_ext = [&](int sfx) {
    if (sfx < 28) return 0;
    int v = 0;
    for (int i = 0; i < 4; ++i) v |= vbit() << i;
    return v;
  };

  for (int qy = 0; qy < qh; ++qy) {
    const QuadRowKind kind = qy == 0 ? QuadRowKind::Initial : QuadRowKind::Other;
    for (int qx0 = 0; qx0 < qw; qx0 += 2) {
      const int count = std::min(2, qw - qx0);
      int rho[2] = {0, 0}, uoff[2] = {0, 0}, ek[2] = {0, 0}, e1[2] = {0, 0}, u[2] = {0, 0};
      for (int k = 0; k < count; ++k) {
        const int x = 2 * (qx0 + k), y = 2 * qy;
        int c;
        if (qy == 0) {  // formula for the initial line-pair
          c = (at(sigma, x - 2, 0) | at(sigma, x - 2, 1)) + 2 * at(sigma, x - 1, 0) + 4 * at(sigma, x - 1, 1);
        } else {
          c = (at(sigma, x - 1, y - 1) | at(sigma, x, y - 1)) + 2 * (at(sigma, x - 1, y) | at(sigma, x - 1, y + 1)) +
              4 * (at(sigma, x + 1, y - 1) | at(sigma, x + 2, y - 1));
        }
        if (c == 0 && mel.decode() == 0) continue;  // an all-insignificant quad
        const CxtVlcRow& r = find_row(kind, c);
        rho[k] = r.rho, uoff[k] = r.u_off, ek[k] = r.e_k, e1[k] = r.e_1;
        for (int n = 0; n < 4; ++n) sigma[static_cast<std::size_t>((y + dy[n]) * pw + x + dx[n])] = (rho[k] >> n) & 1;
      }
      if (count == 2 && uoff[0] && uoff[1] && qy == 0) {
        if (mel.decode()) {
          const int p0 = u_prefix(), p1 = u_prefix();
          const int s0 = u_suffix(p0), s1 = u_suffix(p1);
          u[0] = 2 + p0 + s0 + 4 * u_ext(s0);
          u[1] = 2 + p1 + s1 + 4 * u_ext(s1);
        } else {
          const int p0 = u_prefix();
          if (p0 > 2) {
            u[1] = vbit() + 1;
            const int s0 = u_suffix(p0);
            u[0] = p0 + s0 + 4 * u_ext(s0);
          } else {
            const int p1 = u_prefix();
            const int s0 = u_suffix(p0), s1 = u_suffix(p1);
            u[0] = p0 + s0 + 4 * u_ext(s0);
            u[1] = p1 + s1 + 4 * u_ext(s1);
          }
        }
      } else {
        int pfx[2] = {0, 0}, sfx[2] = {0, 0};
        for (int k = 0; k < count; ++k)
          if (uoff[k]) pfx[k] = u_prefix();
        for (int k = 0; k < count; ++k)
          if (uoff[k]) sfx[k] = u_suffix(pfx[k]);
        for (int k = 0; k < count; ++k)
          if (uoff[k]) u[k] = pfx[k] + sfx[k] + 4 * u_ext(sfx[k]);
      }
      for (int k = 0; k < count; ++k) {
        const int x = 2 * (qx0 + k), y = 2 * qy;
        int kappa = 1;
        if (qy > 0 && (rho[k] & (rho[k] - 1)) != 0) {
          int emax = 0;
          for (int ddx = -1; ddx <= 2; ++ddx) emax = std::max(emax, at(expo, x + ddx, y - 1));
          kappa = std::max(1, emax - 1);
        }
        const int big_u = kappa + u[k];
        for (int n = 0; n < 4; ++n) {
          if (!((rho[k] >> n) & 1)) continue;
          const int m = big_u - ((ek[k] >> n) & 1);
          std::uint64_t v = magsgn.read(m);
          v |= static_cast<std::uint64_t>((e1[k] >> n) & 1) << m;
          const auto i = static_cast<std::size_t>((y + dy[n]) * pw + x + dx[n]);
          mu[i] = static_cast<std::uint32_t>((v >> 1) + 1);
          neg[i] = static_cast<int>(v & 1);
          expo[i] = exponent_of(mu[i]);
          if (uoff[k]) {
            EXPECT_LE(expo[i], big_u);
          }
        }
        if (uoff[k]) {  // with a residual, U_q is the quad's largest exponent
          int emax = 0;
          for (int n = 0; n < 4; ++n) emax = std::max(emax, at(expo, x + dx[n], y + dy[n]));
          EXPECT_EQ(emax, big_u);
        }
      }
    }
  }
  Decoded out;
  for (int y = 0; y < ph; ++y)
    for (int x = 0; x < pw; ++x) {
      const auto i = static_cast<std::size_t>(y * pw + x);
      if (x >= width || y >= height) {
        EXPECT_EQ(sigma[i], 0) << "a sample outside the block is significant";
        continue;
      }
      out.mu.push_back(mu[i]);
      out.negative.push_back(neg[i]);
    }
  return out;
}

// ---- The refinement passes' model decoder ------------------------------------------------------

// SigProp bits (T.814 7.1.5): forwards from the refinement segment's start, least significant bit
// first; a byte after 0xFF gives 7 bits; 0s past the segment (`size` bytes: a decoder given only
// the SigProp pass sees the segment end after it).
class SigPropReader {
 public:
  SigPropReader(const std::vector<std::uint8_t>& d, std::size_t start, std::size_t size)
      : d_(d), pos_(start), end_(start + size) {}
  int bit() {
    if (left_ == 0) {
      current_ = pos_ < end_ ? d_[pos_] : 0;
      ++pos_;
      left_ = previous_ff_ ? 7 : 8;
      previous_ff_ = current_ == 0xFF;
      used_ = 0;
    }
    --left_;
    return static_cast<int>((current_ >> used_++) & 1);
  }

 private:
  const std::vector<std::uint8_t>& d_;
  std::size_t pos_, end_;
  int left_ = 0, used_ = 0;
  unsigned current_ = 0;
  bool previous_ff_ = false;
};

// MagRef bits (T.814 7.1.6): backwards from the segment's last byte, least significant bit first;
// a byte whose predecessor (in reading order, and before the first: as if one above 0x8F) exceeds
// 0x8F and whose low 7 bits are all 1 gives 7 bits; 0s past the segment's start.
class MagRefReader {
 public:
  MagRefReader(const std::vector<std::uint8_t>& d, std::size_t start, std::size_t size)
      : d_(d), start_(start), pos_(start + size) {}
  int bit() {
    if (left_ == 0) {
      current_ = pos_ > start_ ? d_[--pos_] : 0;
      left_ = previous_big_ && (current_ & 0x7F) == 0x7F ? 7 : 8;
      previous_big_ = current_ > 0x8F;
      used_ = 0;
    }
    --left_;
    return static_cast<int>((current_ >> used_++) & 1);
  }

 private:
  const std::vector<std::uint8_t>& d_;
  std::size_t start_, pos_;
  int left_ = 0, used_ = 0;
  unsigned current_ = 0;
  bool previous_big_ = true;
};

// What a decoder knows of each sample after the cleanup (`cleanup`, plane p) and the refinement
// passes of plane q = p - 1: mu at plane q (0: not known significant) and its sign. The SigProp
// pass, as T.814 7.4 describes it: stripes of 4 rows, groups of 4 columns; in a group, column by
// column and top to bottom, a sample not significant in the cleanup with one of its 8 neighbours
// significant (in the cleanup, or by an earlier decision of this pass) reads its bit; then the
// group's new significant samples read their signs. MagRef (7.5): stripes of 4 rows, column by
// column, every sample significant in the cleanup reads its next bit.
Decoded decode_refinement(const Decoded& cleanup, const std::vector<std::uint8_t>& d, std::size_t start,
                          std::size_t sigprop_size, std::size_t segment_size, bool with_magref, int width, int height) {
  Decoded out;
  out.mu.assign(cleanup.mu.size(), 0);
  out.negative = cleanup.negative;
  out.read.assign(cleanup.mu.size(), 0);
  std::vector<int> state(cleanup.mu.size(), 0);  // 1: significant in the cleanup, 2: made so by SigProp
  for (std::size_t i = 0; i < cleanup.mu.size(); ++i) {
    state[i] = cleanup.mu[i] != 0 ? 1 : 0;
    out.mu[i] = 2 * cleanup.mu[i];  // the refined bit is added below (or is unknown: left 0)
  }
  auto significant = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height && state[static_cast<std::size_t>(y * width + x)] != 0;
  };
  if (with_magref) {
    MagRefReader magref(d, start, segment_size);
    for (int y0 = 0; y0 < height; y0 += 4)
      for (int x = 0; x < width; ++x)
        for (int y = y0; y < std::min(y0 + 4, height); ++y)
          if (state[static_cast<std::size_t>(y * width + x)] == 1)
            out.mu[static_cast<std::size_t>(y * width + x)] |= static_cast<std::uint32_t>(magref.bit());
  }
  SigPropReader sigprop(d, start, sigprop_size);
  for (int y0 = 0; y0 < height; y0 += 4)
    for (int x0 = 0; x0 < width; x0 += 4) {
      std::vector<std::size_t> fresh;
      for (int x = x0; x < std::min(x0 + 4, width); ++x)
        for (int y = y0; y < std::min(y0 + 4, height); ++y) {
          const auto i = static_cast<std::size_t>(y * width + x);
          if (state[i] != 0) continue;
          bool neighbour = false;
          for (int dy2 = -1; dy2 <= 1; ++dy2)
            for (int dx2 = -1; dx2 <= 1; ++dx2)
              neighbour = neighbour || ((dx2 != 0 || dy2 != 0) && significant(x + dx2, y + dy2));
          if (neighbour) out.read[i] = 1;
          if (neighbour && sigprop.bit()) {
            state[i] = 2;
            out.mu[i] = 1;
            fresh.push_back(i);
          }
        }
      for (std::size_t i : fresh) out.negative[i] = sigprop.bit();
    }
  return out;
}

// Squared error of a sample of magnitude m known as mu at plane q (mid-point reconstruction; at
// plane 0 an integer index is exact).
double squared_error(std::uint32_t m, std::uint32_t mu, int q) {
  const double step = std::ldexp(1.0, q);
  const double rebuilt = mu == 0 ? 0.0 : static_cast<double>(mu) * step + (q > 0 ? step / 2 : 0.0);
  return (static_cast<double>(m) - rebuilt) * (static_cast<double>(m) - rebuilt);
}

// ---- Random blocks -----------------------------------------------------------------------------

// A block whose largest magnitude has exactly `planes` bits; a mix of zero runs, small values and
// large ones, with a density that varies from block to block, so that MEL runs, every context and
// the U-VLC extension all occur.
std::vector<std::int32_t> random_block(std::mt19937& rng, int width, int height, int planes) {
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::int32_t> block(n, 0);
  if (planes == 0) return block;
  const double density = std::uniform_real_distribution<double>(0.02, 1.0)(rng);
  std::bernoulli_distribution present(density), negative(0.5);
  std::uniform_int_distribution<int> bits(1, planes);
  for (auto& v : block) {
    if (!present(rng)) continue;
    const int b = bits(rng);
    const std::uint32_t top = std::uint32_t{1} << (b - 1);
    const std::uint32_t m = top | (static_cast<std::uint32_t>(rng()) & (top - 1));
    v = negative(rng) ? -static_cast<std::int32_t>(m) : static_cast<std::int32_t>(m);
  }
  const std::uint32_t peak = (std::uint32_t{1} << (planes - 1)) |
                             (static_cast<std::uint32_t>(rng()) & ((std::uint32_t{1} << (planes - 1)) - 1));
  block[static_cast<std::size_t>(rng() % n)] = static_cast<std::int32_t>(peak);
  return block;
}

std::vector<std::pair<int, int>> all_shapes() {
  std::vector<std::pair<int, int>> shapes;
  for (int w = 1; w <= 1024; w *= 2)
    for (int h = 1; h <= 1024; h *= 2)
      if (w * h <= 4096) shapes.emplace_back(w, h);
  // Edge blocks: odd sizes, where quads overhang the right and bottom edges.
  for (auto s : {std::pair{3, 3}, {5, 7}, {7, 5}, {1, 3}, {3, 1}, {33, 31}, {63, 63}, {1023, 1}, {1, 1023}, {5, 819}})
    shapes.push_back(s);
  return shapes;
}

void expect_no_marker(const std::vector<std::uint8_t>& d, const std::string& where) {
  for (std::size_t i = 0; i + 1 < d.size(); ++i)
    if (d[i] == 0xFF && d[i + 1] > 0x8F) {
      ADD_FAILURE() << where << ": bytes " << i << ", " << i + 1 << " form a marker";
      return;
    }
}

void check_round_trip(const std::vector<std::int32_t>& block, int width, int height, int planes, int p,
                      const std::string& where) {
  const int mb = std::max(planes, p + 1);
  const codec::t1::EncodedBlock eb = codec::ht::encode_ht_block(block, width, height, mb, p);
  ASSERT_EQ(eb.bit_planes, planes) << where;
  if (planes <= p) {
    EXPECT_TRUE(eb.passes.empty()) << where;
    EXPECT_EQ(eb.missing_msbs, mb) << where;
    return;
  }
  ASSERT_EQ(eb.passes.size(), 1u) << where;
  EXPECT_EQ(eb.passes[0].length, eb.data.size()) << where;
  EXPECT_TRUE(eb.passes[0].terminated) << where;
  EXPECT_EQ(eb.missing_msbs, mb - 1 - p) << where;
  EXPECT_EQ(eb.first_pass_planes, planes - p) << where;
  if (p == 0) {
    EXPECT_DOUBLE_EQ(eb.passes[0].distortion_decrease, eb.energy) << where;
  }
  expect_no_marker(eb.data, where);
  const Decoded d = decode_cleanup(eb.data, width, height);
  ASSERT_EQ(d.mu.size(), block.size()) << where;
  for (std::size_t i = 0; i < block.size(); ++i) {
    const std::uint32_t m = block[i] < 0 ? static_cast<std::uint32_t>(-static_cast<std::int64_t>(block[i]))
                                         : static_cast<std::uint32_t>(block[i]);
    const std::uint32_t expected = m >> p;
    if (d.mu[i] != expected || (expected != 0 && d.negative[i] != (block[i] < 0 ? 1 : 0))) {
      ADD_FAILURE() << where << ": sample " << i << " (" << i % static_cast<std::size_t>(width) << ", "
                    << i / static_cast<std::size_t>(width) << ") decodes to " << (d.negative[i] ? "-" : "") << d.mu[i]
                    << ", expected " << (block[i] < 0 ? "-" : "") << expected;
      return;
    }
  }
}

// A block coded from plane p with its refinement passes (HtPasses::CleanupAndRefinement): the
// model decodes the cleanup from pass 1's bytes, then the refinement segment both as a decoder given
// 2 passes sees it (SigProp alone, the segment cut after its bytes) and as one given 3. Every sample
// significant in the cleanup or visited by SigProp must come out exact at plane p - 1, with its
// sign; the others (no significant neighbour) known as 0 at that plane; and each pass's distortion
// decrease must be what the model's reconstruction gives.
void check_refinement(const std::vector<std::int32_t>& block, int width, int height, int planes, int p,
                      const std::string& where) {
  const codec::t1::EncodedBlock eb =
      codec::ht::encode_ht_block(codec::ht::load_ht_block(block, width, height), 31, p, codec::t1::Distortion::Measured,
                                 codec::ht::HtPasses::CleanupAndRefinement);
  if (planes <= p) {
    EXPECT_TRUE(eb.passes.empty()) << where;
    return;
  }
  ASSERT_EQ(eb.passes.size(), 3u) << where;
  const std::size_t l0 = eb.passes[0].length, l1 = eb.passes[1].length, l2 = eb.passes[2].length;
  ASSERT_LE(l0, l1) << where;
  ASSERT_LT(l1, l2) << where;  // MagRef has a bit for every sample the cleanup made significant
  ASSERT_EQ(l2, eb.data.size()) << where;
  expect_no_marker(eb.data, where);
  for (std::size_t end : {l0, l1, l2}) {
    EXPECT_NE(eb.data[end - 1], 0xFF) << where << ": a pass ends in 0xFF";
  }
  const std::vector<std::uint8_t> cleanup_bytes(eb.data.begin(), eb.data.begin() + static_cast<std::ptrdiff_t>(l0));
  const Decoded cleanup = decode_cleanup(cleanup_bytes, width, height);
  ASSERT_EQ(cleanup.mu.size(), block.size()) << where;
  const Decoded two = decode_refinement(cleanup, eb.data, l0, l1 - l0, l1 - l0, false, width, height);
  const Decoded three = decode_refinement(cleanup, eb.data, l0, l2 - l0, l2 - l0, true, width, height);
  double before = 0, after_sigprop = 0, after_magref = 0;
  for (std::size_t i = 0; i < block.size(); ++i) {
    const std::uint32_t m = block[i] < 0 ? static_cast<std::uint32_t>(-static_cast<std::int64_t>(block[i]))
                                         : static_cast<std::uint32_t>(block[i]);
    const int neg = block[i] < 0 ? 1 : 0;
    const std::uint32_t exact = m >> (p - 1);
    const bool in_cleanup = cleanup.mu[i] != 0;
    // SigProp: new significance and sign exact where read; what it did not read stays 0.
    const std::uint32_t sp = in_cleanup ? 0 : two.mu[i];
    // A sample read must receive its own bit: an encoder that sent 0s would decode consistently.
    if ((sp != 0 || two.read[i]) && (sp != exact || (sp != 0 && two.negative[i] != neg))) {
      ADD_FAILURE() << where << ": sample " << i << " SigProp gives " << (two.negative[i] ? "-" : "") << sp
                    << ", expected " << exact;
      return;
    }
    if (in_cleanup ? three.mu[i] != exact : three.mu[i] != two.mu[i]) {
      ADD_FAILURE() << where << ": sample " << i << " after MagRef " << three.mu[i] << ", expected " << exact;
      return;
    }
    before += squared_error(m, cleanup.mu[i], p);
    after_sigprop += in_cleanup ? squared_error(m, cleanup.mu[i], p) : squared_error(m, sp, p - 1);
    after_magref += in_cleanup ? squared_error(m, three.mu[i], p - 1) : squared_error(m, sp, p - 1);
  }
  // Samples left unread must be those with no significant neighbour: the model found exactly the
  // encoder's members, or the streams would have desynchronised above. Distortion decreases:
  const double tolerance = 1e-9 * std::max(1.0, before);
  EXPECT_NEAR(eb.passes[1].distortion_decrease, before - after_sigprop, tolerance) << where;
  EXPECT_NEAR(eb.passes[2].distortion_decrease, after_sigprop - after_magref, tolerance) << where;
}

// ---- Tests -------------------------------------------------------------------------------------

TEST(HtTables, EachContextIsACompletePrefixCodeWithConsistentPatterns) {
  for (QuadRowKind kind : {QuadRowKind::Initial, QuadRowKind::Other}) {
    const auto rows = codec::ht::cxt_vlc_rows(kind);
    EXPECT_EQ(rows.size(), kind == QuadRowKind::Initial ? 444u : 358u);
    for (int c = 0; c < 8; ++c) {
      double kraft = 0;
      std::vector<CxtVlcRow> in_context;
      for (const CxtVlcRow& r : rows)
        if (r.context == c) in_context.push_back(r);
      for (const CxtVlcRow& r : in_context) {
        ASSERT_GE(r.length, 1);
        ASSERT_LE(r.length, 7);
        kraft += 1.0 / (1 << r.length);
        EXPECT_EQ(r.e_k & ~r.rho, 0) << "e_k outside rho";
        EXPECT_EQ(r.e_1 & ~r.e_k, 0) << "e_1 outside e_k";
        if (!r.u_off) {
          EXPECT_EQ(r.e_k, 0);
        }
        if (c == 0) {
          EXPECT_NE(r.rho, 0) << "context 0's empty quad is the MEL's";
        }
        for (const CxtVlcRow& s : in_context)
          if (&s != &r && s.length >= r.length) {
            EXPECT_NE(s.codeword & ((1 << r.length) - 1), r.codeword) << "a codeword prefixes another in context " << c;
          }
      }
      EXPECT_DOUBLE_EQ(kraft, 1.0) << "context " << c;
    }
  }
}

TEST(HtBlock, EveryShapeAndBitPlaneCountDecodesExactly) {
  std::mt19937 rng(20261201);
  for (const auto& [w, h] : all_shapes())
    for (int planes = 0; planes <= 31; ++planes) {
      const auto block = random_block(rng, w, h, planes);
      check_round_trip(block, w, h, planes, 0,
                       std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(planes) + " planes");
      if (HasFailure()) return;
    }
}

TEST(HtBlock, CleanupOnAHigherPlaneCodesTheMagnitudesAboveIt) {
  std::mt19937 rng(7);
  for (const auto& [w, h] : {std::pair{64, 64}, {32, 16}, {7, 9}, {1024, 4}, {4, 1024}})
    for (int planes = 1; planes <= 31; planes += 3)
      for (int p : {1, 2, 5, planes - 1, planes, planes + 2}) {
        if (p < 0 || p > 30) continue;
        const auto block = random_block(rng, w, h, planes);
        check_round_trip(block, w, h, planes, p,
                         std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(planes) + " planes, p " +
                             std::to_string(p));
        if (HasFailure()) return;
      }
}

TEST(HtBlock, SparseAndDenseExtremes) {
  // All-significant blocks of one large value (every quad at the U-VLC extension), lone samples
  // in long zero runs (the MEL at its highest state), and a checkerboard.
  for (std::int32_t v : {1, -1, 2, 3, 1 << 20, -(1 << 30), 0x7FFFFFFF}) {
    std::vector<std::int32_t> full(4096, v);
    check_round_trip(full, 64, 64,
                     std::bit_width(static_cast<std::uint32_t>(v < 0 ? -static_cast<std::int64_t>(v) : v)), 0,
                     "constant " + std::to_string(v));
  }
  std::vector<std::int32_t> lone(4096, 0);
  lone[4095] = -5;
  lone[2000] = 9;
  check_round_trip(lone, 64, 64, 4, 0, "two lone samples");
  std::vector<std::int32_t> board(4096);
  for (int i = 0; i < 4096; ++i) board[static_cast<std::size_t>(i)] = ((i / 64 + i) % 2) ? 100 + i % 7 : 0;
  check_round_trip(board, 64, 64, 7, 0, "checkerboard");
}

TEST(HtBlock, FloatAndIntegerBlocksInPlaceMatchTheSpanCoder) {
  std::mt19937 rng(3);
  const int w = 20, h = 12, stride = 33;
  std::vector<std::int32_t> plane(static_cast<std::size_t>(stride * h));
  std::vector<float> fplane(plane.size());
  for (std::size_t i = 0; i < plane.size(); ++i) {
    plane[i] = static_cast<std::int32_t>(rng() % 2001) - 1000;
    fplane[i] = static_cast<float>(plane[i]) * 0.37f;
  }
  std::vector<std::int32_t> packed;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) packed.push_back(plane[static_cast<std::size_t>(y * stride + x)]);
  const auto a = codec::ht::encode_ht_block(codec::t1::IntegerBlock{plane.data(), stride, w, h}, 12);
  const auto b = codec::ht::encode_ht_block(packed, w, h, 12);
  EXPECT_EQ(a.data, b.data);
  const auto f = codec::ht::encode_ht_block(codec::t1::FloatBlock{fplane.data(), stride, w, h, 1 / 0.37f}, 12);
  ASSERT_EQ(f.passes.size(), 1u);
  EXPECT_GT(f.passes[0].distortion_decrease, 0.9 * f.energy);
  EXPECT_LE(f.passes[0].distortion_decrease, f.energy);
}

// A float block's bit lengths come from the quantiser's float exponents (simd::quantize_row), not
// from the indices: they must be the indices' bit lengths, with and without the top bit, at every
// power of two and either side of it, below 1, at the clamp, for NaN and infinities.
TEST(HtBlock, FloatLoadsMeasureTheIndicesBitLengths) {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               1e-30f,
                               0.5f,
                               0.99999994f,
                               1.0f,
                               -1.0f,
                               1.5f,
                               2.0f,
                               3.0f,
                               3.9999998f,
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(),
                               2147483520.0f,
                               3e9f,
                               -3e9f};
  for (int k = 1; k < 31; ++k) {
    const float power = std::ldexp(1.0f, k);
    for (const float v : {power, std::nextafter(power, 0.0f), std::nextafter(power, 1e10f), power * 1.5f,
                          std::nextafter(power * 2, 0.0f), -power - 1})
      values.push_back(v);
  }
  std::mt19937 rng(29);
  while (values.size() % 64 != 0 || values.size() < 256)
    values.push_back(std::ldexp(std::uniform_real_distribution<float>(-1, 1)(rng), static_cast<int>(rng() % 32)));
  const int w = 64, h = static_cast<int>(values.size() / 64);
  for (const float inverse_step : {1.0f, 0.37f}) {
    const auto b = codec::ht::load_ht_block(codec::t1::FloatBlock{values.data(), w, w, h, inverse_step});
    // Rate control skips planes on the load's energy bound: it must be no less than the energy.
    double energy = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double v = b.magnitudes[i] + b.fractions[i] / 256.0;
      energy += v * v;
    }
    EXPECT_GE(b.energy_bound, energy) << "x " << inverse_step;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::uint32_t m = b.magnitudes[i];
      const int l = static_cast<int>(std::bit_width(m));
      const int below = static_cast<int>(std::bit_width(l > 0 ? m ^ (std::uint32_t{1} << (l - 1)) : 0u));
      ASSERT_EQ(b.lengths[i], l) << values[i] << " x " << inverse_step << ": index " << m;
      ASSERT_EQ(b.lengths_below_top[i], below) << values[i] << " x " << inverse_step << ": index " << m;
    }
  }
}

// Rate control loads each block into one block a worker keeps (load_ht_block into a reused
// HtBlock): whatever shape, kind and content the block held before, the reused block must equal a
// fresh load, fractions emptied for an integer block included.
TEST(HtBlock, LoadingIntoAReusedBlockEqualsAFreshLoad) {
  std::mt19937 rng(11);
  const int stride = 70;
  std::vector<std::int32_t> plane(static_cast<std::size_t>(stride * 64));
  std::vector<float> fplane(plane.size());
  for (std::size_t i = 0; i < plane.size(); ++i) {
    plane[i] = static_cast<std::int32_t>(rng() % 4001) - 2000;
    fplane[i] = static_cast<float>(plane[i]) * 0.61f;
  }
  auto expect_same = [](const codec::ht::HtBlock& got, const codec::ht::HtBlock& fresh, const std::string& what) {
    EXPECT_EQ(got.width, fresh.width) << what;
    EXPECT_EQ(got.height, fresh.height) << what;
    EXPECT_EQ(got.bit_planes, fresh.bit_planes) << what;
    EXPECT_EQ(got.magnitudes, fresh.magnitudes) << what;
    EXPECT_EQ(got.negative, fresh.negative) << what;
    EXPECT_EQ(got.fractions, fresh.fractions) << what;
    EXPECT_EQ(got.lengths, fresh.lengths) << what;
    EXPECT_EQ(got.lengths_below_top, fresh.lengths_below_top) << what;
  };
  codec::ht::HtBlock reused;
  const struct {
    int w, h;
    bool floats;
  } loads[] = {{64, 64, true}, {5, 3, true}, {64, 64, false}, {17, 9, true}, {1, 1, false}, {64, 64, true}};
  for (const auto& l : loads) {
    const std::string what = std::to_string(l.w) + "x" + std::to_string(l.h) + (l.floats ? " float" : " integer");
    if (l.floats) {
      const codec::t1::FloatBlock block{fplane.data(), stride, l.w, l.h, 1 / 0.61f};
      codec::ht::load_ht_block(block, reused);
      expect_same(reused, codec::ht::load_ht_block(block), what);
    } else {
      const codec::t1::IntegerBlock block{plane.data(), stride, l.w, l.h};
      codec::ht::load_ht_block(block, reused);
      expect_same(reused, codec::ht::load_ht_block(block), what);
      EXPECT_TRUE(reused.fractions.empty()) << what;
    }
  }
}

// SigProp and MagRef after cleanups from every plane a block can have one from, on every shape
// and bit-plane count.
TEST(HtBlock, RefinementPassesDecodeExactlyOnEveryShapeAndPlane) {
  std::mt19937 rng(20261125);
  for (const auto& [w, h] : all_shapes())
    for (int planes = 1; planes <= 31; ++planes) {
      const auto block = random_block(rng, w, h, planes);
      const int p = 1 + static_cast<int>(rng() % static_cast<unsigned>(planes));  // 1..planes: planes gives no pass
      check_refinement(block, w, h, planes, p,
                       std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(planes) + " planes, p " +
                           std::to_string(p));
      if (HasFailure()) return;
    }
  // Every cleanup plane of one block per shape family, dense and sparse.
  for (const auto& [w, h] : {std::pair{64, 64}, {5, 7}, {1024, 4}, {4, 1024}, {33, 31}})
    for (int p = 1; p <= 12; ++p) {
      const auto block = random_block(rng, w, h, 12);
      check_refinement(block, w, h, 12, p,
                       std::to_string(w) + "x" + std::to_string(h) + ", 12 planes, p " + std::to_string(p));
      if (HasFailure()) return;
    }
}

// The magnitudes an irreversible block's cleanup on plane p codes (ht_block_encoder.cpp, README
// "Raising near-significant samples" and "Lowering quads' exponents"), from the rules as the README
// writes them, sample by sample. `raise`: the cleanup is the last pass. Counts what it changed.
std::vector<std::uint32_t> adjusted_magnitudes(const codec::ht::HtBlock& b, int p, bool raise, std::size_t& raised,
                                               std::size_t& lowered) {
  const int w = b.width, h = b.height;
  const std::uint32_t unit = std::uint32_t{1} << p;
  std::vector<std::uint32_t> m = b.magnitudes;
  auto at = [&](int x, int y) { return static_cast<std::size_t>(y * w + x); };
  auto key = [&](std::size_t i) { return std::uint64_t{b.magnitudes[i]} * 256 + b.fractions[i]; };
  auto exponent = [&](std::size_t i) { return static_cast<int>(exponent_of(m[i] >> p)); };
  for (int y0 = 0; y0 < h; y0 += 2)
    for (int x0 = 0; x0 < w; x0 += 2) {
      std::vector<std::size_t> quad;
      for (int y = y0; y < std::min(y0 + 2, h); ++y)
        for (int x = x0; x < std::min(x0 + 2, w); ++x) quad.push_back(at(x, y));
      bool significant = false;
      for (const std::size_t i : quad) significant |= m[i] >= unit;
      // Raising: from 0.9 u up, in quads already significant.
      if (raise && significant)
        for (const std::size_t i : quad)
          if (m[i] < unit && static_cast<double>(key(i)) >= std::ceil(0.9 * unit * 256)) {
            m[i] = unit;
            ++raised;
          }
      // Lowering: the largest exponent's samples, all at its smallest index, offsets under a tenth
      // of a step per significant sample, and above kappa.
      int emax = 0, count = 0;
      for (const std::size_t i : quad) {
        emax = std::max(emax, exponent(i));
        count += m[i] >= unit ? 1 : 0;
      }
      int kappa = 1;
      if (y0 > 0 && count > 1) {
        int above = 0;
        for (int x = std::max(0, x0 - 1); x < std::min(w, x0 + 3); ++x)
          above = std::max(above, exponent(at(x, y0 - 1)));
        kappa = std::max(1, above - 1);
      }
      if (emax < 2 || emax <= kappa) continue;
      const std::uint32_t lowest = (std::uint32_t{1} << (emax - 2)) + 1;
      // Offsets in 256ths of a step, rounded down.
      std::uint64_t offsets = 0;
      bool all_lowest = true;
      for (const std::size_t i : quad)
        if (exponent(i) == emax) {
          all_lowest &= (m[i] >> p) == lowest;
          offsets += (key(i) - std::uint64_t{lowest} * unit * 256) >> p;
        }
      if (!all_lowest || offsets * 10 >= std::uint64_t{static_cast<unsigned>(count)} * 256) continue;
      for (const std::size_t i : quad)
        if (exponent(i) == emax) {
          m[i] = (lowest << p) - 1;
          ++lowered;
        }
    }
  return m;
}

// Raising and lowering: an irreversible block's cleanup codes the indices of adjusted_magnitudes,
// and SigProp finds every sample it reads significant from 0.85 2^(p-1) up. Checked through this
// file's own decoders, with and without refinement passes; each pass's distortion decrease must be
// what the decoded values leave.
TEST(HtBlock, IrreversibleIndicesAreRaisedAndLoweredWhereThatPays) {
  std::mt19937 rng(20261129);
  std::size_t raised = 0, lowered = 0, raised_by_sigprop = 0;
  for (const auto& [w, h] : {std::pair{64, 64}, {33, 31}, {5, 7}, {4, 1024}, {1024, 4}})
    for (const float inverse_step : {1.0f, 0.37f}) {
      std::vector<float> values(static_cast<std::size_t>(w * h));
      std::exponential_distribution<float> laplace(1.0f);
      for (float& v : values)
        v = (rng() % 2 ? -1.0f : 1.0f) * laplace(rng) * std::ldexp(1.0f, static_cast<int>(rng() % 5));
      const codec::ht::HtBlock b =
          codec::ht::load_ht_block(codec::t1::FloatBlock{values.data(), w, w, h, inverse_step});
      const auto n = values.size();
      auto value = [&](std::size_t i) { return b.magnitudes[i] + b.fractions[i] / 256.0; };
      double energy = 0;
      for (std::size_t i = 0; i < n; ++i) energy += value(i) * value(i);
      auto rebuilt = [](std::uint32_t mu, int q) { return mu == 0 ? 0.0 : (mu + 0.5) * std::ldexp(1.0, q); };
      auto error = [&](std::size_t i, std::uint32_t mu, int q) {
        return (value(i) - rebuilt(mu, q)) * (value(i) - rebuilt(mu, q));
      };
      for (const int p : {0, 1, 3}) {
        const std::string where = std::to_string(w) + "x" + std::to_string(h) + " / " + std::to_string(inverse_step) +
                                  ", p " + std::to_string(p);
        const double unit = std::ldexp(1.0, p);
        const auto cleanup_only =
            codec::ht::encode_ht_block(b, 31, p, codec::t1::Distortion::Measured, codec::ht::HtPasses::Cleanup);
        if (cleanup_only.passes.empty()) continue;
        const std::vector<std::uint32_t> last = adjusted_magnitudes(b, p, true, raised, lowered);
        const Decoded c = decode_cleanup(cleanup_only.data, w, h);
        double left = 0;
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(c.mu[i], last[i] >> p) << where << ", sample " << i << " (" << value(i) << ")";
          if (c.mu[i] != 0) {
            ASSERT_EQ(c.negative[i], values[i] < 0 ? 1 : 0) << where << ", sample " << i;
          }
          left += error(i, c.mu[i], p);
        }
        EXPECT_NEAR(cleanup_only.passes[0].distortion_decrease, energy - left, 1e-9 * energy) << where;
        if (p == 0) continue;
        const auto refined = codec::ht::encode_ht_block(b, 31, p, codec::t1::Distortion::Measured,
                                                        codec::ht::HtPasses::CleanupAndRefinement);
        ASSERT_EQ(refined.passes.size(), 3u) << where;
        const std::vector<std::uint32_t> first = adjusted_magnitudes(b, p, false, raised, lowered);
        const std::size_t l0 = refined.passes[0].length, l1 = refined.passes[1].length, l2 = refined.data.size();
        const Decoded plain = decode_cleanup(
            std::vector<std::uint8_t>(refined.data.begin(), refined.data.begin() + static_cast<std::ptrdiff_t>(l0)), w,
            h);
        const Decoded sigprop = decode_refinement(plain, refined.data, l0, l1 - l0, l1 - l0, false, w, h);
        const Decoded magref = decode_refinement(plain, refined.data, l0, l1 - l0, l2 - l0, true, w, h);
        double after_cleanup = 0, after_sigprop = 0, after_magref = 0;
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(plain.mu[i], first[i] >> p) << where << ", sample " << i << " (" << value(i) << ")";
          const double e = error(i, plain.mu[i], p);
          after_cleanup += e;
          if (plain.mu[i] != 0) {
            // MagRef: bit p - 1 of the coded magnitude (a lowered one's is 1).
            ASSERT_EQ(magref.mu[i], first[i] >> (p - 1)) << where << ", sample " << i;
            after_sigprop += e;
            after_magref += error(i, magref.mu[i], p - 1);
            continue;
          }
          const bool expected = value(i) >= 0.85 * unit / 2;
          if (sigprop.read[i]) {
            ASSERT_EQ(sigprop.mu[i], expected ? 1u : 0u) << where << ", sample " << i << " (" << value(i) << ")";
            raised_by_sigprop += expected && (b.magnitudes[i] >> (p - 1)) == 0;
          }
          if (sigprop.mu[i] != 0) {
            ASSERT_EQ(sigprop.negative[i], values[i] < 0 ? 1 : 0) << where << ", sample " << i;
          }
          after_sigprop += error(i, sigprop.mu[i], p - 1);
          after_magref += error(i, sigprop.mu[i], p - 1);
        }
        EXPECT_NEAR(refined.passes[0].distortion_decrease, energy - after_cleanup, 1e-9 * energy) << where;
        EXPECT_NEAR(refined.passes[1].distortion_decrease, after_cleanup - after_sigprop, 1e-9 * energy) << where;
        EXPECT_NEAR(refined.passes[2].distortion_decrease, after_sigprop - after_magref, 1e-9 * energy) << where;
      }
    }
  // The rules must have had work to do, or this test proves nothing.
  EXPECT_GT(raised, 100u);
  EXPECT_GT(lowered, 100u);
  EXPECT_GT(raised_by_sigprop, 100u);
}

// An integer (reversible) block's indices are the data: nothing is raised at any plane.
TEST(HtBlock, IntegerBlocksAreNeverRaised) {
  std::mt19937 rng(5);
  std::vector<std::int32_t> block(64 * 64);
  for (auto& v : block) v = static_cast<std::int32_t>(rng() % 41) - 20;
  for (const int p : {0, 1, 2}) {
    const auto eb = codec::ht::encode_ht_block(codec::ht::load_ht_block(block, 64, 64), 31, p,
                                               codec::t1::Distortion::Measured, codec::ht::HtPasses::Cleanup);
    const Decoded c = decode_cleanup(eb.data, 64, 64);
    for (std::size_t i = 0; i < block.size(); ++i)
      ASSERT_EQ(c.mu[i], static_cast<std::uint32_t>(std::abs(block[i])) >> p) << "p " << p << ", sample " << i;
  }
}

TEST(HtBlock, RejectsWhatTheStandardDoesNot) {
  std::vector<std::int32_t> big(4097, 1);
  EXPECT_THROW(codec::ht::encode_ht_block(big, 4097, 1, 5), std::invalid_argument);
  std::vector<std::int32_t> small(4, 64);
  EXPECT_THROW(codec::ht::encode_ht_block(small, 2, 2, 5), std::invalid_argument);  // 7 planes > Mb
  EXPECT_THROW(codec::ht::encode_ht_block(small, 2, 2, 8, 8), std::invalid_argument);
}

// ---- Plane statistics --------------------------------------------------------------------------

// What a cleanup from each plane leaves and counts, from the definitions in ht_block_encoder.h,
// sample by sample and plane by plane: the squared error with mid-point reconstruction (a sample
// below 2^p leaves its value; one at or above it (m mod 2^p) + fraction - half, half = 2^(p-1), or
// at p = 0 one half for irreversible coding and 0 otherwise), the quads and samples significant
// at p, and each significant sample's U_q = bit length of 2 (L >> p) - 1, L its quad's largest
// magnitude (T.814 7.3.7). The last entry is for nothing coded: the block's energy.
std::vector<codec::ht::PlaneStatistics> statistics_by_definition(const std::vector<std::int32_t>& block,
                                                                 const std::vector<std::uint8_t>& fractions, int width,
                                                                 int height, int planes) {
  std::vector<codec::ht::PlaneStatistics> out(static_cast<std::size_t>(planes) + 1);
  auto magnitude = [&](int x, int y) -> std::uint32_t {
    if (x >= width || y >= height) return 0;
    const std::int32_t c = block[static_cast<std::size_t>(y * width + x)];
    return static_cast<std::uint32_t>(c < 0 ? -static_cast<std::int64_t>(c) : c);
  };
  for (int p = 0; p <= planes; ++p) {
    codec::ht::PlaneStatistics& s = out[static_cast<std::size_t>(p)];
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::uint32_t m = magnitude(x, y);
        const double v = m + (fractions.empty() ? 0.0 : fractions[static_cast<std::size_t>(y * width + x)] / 256.0);
        double e = v;
        if (p < planes && (m >> p) != 0) {
          const double half = p > 0 ? std::ldexp(1.0, p - 1) : (fractions.empty() ? 0.0 : 0.5);
          e = v - (std::ldexp(static_cast<double>(m >> p), p) + half);
        }
        s.error += e * e;
      }
    if (p == planes) continue;
    for (int y0 = 0; y0 < height; y0 += 2)
      for (int x0 = 0; x0 < width; x0 += 2) {
        const std::uint32_t quad[4] = {magnitude(x0, y0), magnitude(x0, y0 + 1), magnitude(x0 + 1, y0),
                                       magnitude(x0 + 1, y0 + 1)};
        const std::uint32_t largest = *std::max_element(quad, quad + 4);
        if ((largest >> p) == 0) continue;
        s.significant_quads += 1;
        const int u = static_cast<int>(std::bit_width(2 * (largest >> p) - 1));
        for (const std::uint32_t m : quad)
          if ((m >> p) != 0) s.significant_samples += 1, s.magnitude_bits += u;
      }
  }
  return out;
}

// ht::plane_statistics (rate control's estimates: SIMD error sums over each chunk's own planes,
// SIMD quad counts plane by plane over whole chunks of columns and difference arrays over the rest)
// agrees with the definitions on random blocks of every shape and bit-plane count, with and
// without fractions.
TEST(HtBlock, PlaneStatisticsMatchTheirDefinitions) {
  std::mt19937 rng(20261127);
  for (const auto& [w, h] : all_shapes()) {
    for (int planes : {0, 1, 2, 5, 9, 17, 30, 31}) {
      const auto block = random_block(rng, w, h, planes);
      for (const bool irreversible : {false, true}) {
        std::vector<std::uint8_t> fractions;
        if (irreversible)
          for (std::size_t i = 0; i < block.size(); ++i) fractions.push_back(static_cast<std::uint8_t>(rng()));
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(planes) + " planes" +
                     (irreversible ? ", with fractions" : ""));
        const auto got = codec::ht::plane_statistics(codec::ht::load_ht_block(block, w, h, fractions));
        const auto want = statistics_by_definition(block, fractions, w, h, planes);
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t p = 0; p < want.size(); ++p) {
          SCOPED_TRACE("plane " + std::to_string(p));
          // The energy (nothing coded) exactly; the other planes' errors are estimates summed in
          // float (simd::plane_errors): within 1e-5 of the energy (rounding of the values above 2^24
          // and of sums of up to 128 terms a lane, each some 6e-8 relative).
          const double tolerance = (p + 1 == want.size() ? 1e-12 : 1e-5) * std::max(1.0, want.back().error);
          EXPECT_NEAR(got[p].error, want[p].error, tolerance);
          EXPECT_EQ(got[p].significant_quads, want[p].significant_quads);
          EXPECT_EQ(got[p].significant_samples, want[p].significant_samples);
          EXPECT_EQ(got[p].magnitude_bits, want[p].magnitude_bits);
        }
        // In two steps with the errors from a plane up: the same there, that plane's below it.
        if (planes < 2) continue;
        const int lowest = planes / 2;
        auto partial = codec::ht::plane_counts(codec::ht::load_ht_block(block, w, h, fractions));
        codec::ht::add_plane_errors(codec::ht::load_ht_block(block, w, h, fractions), partial, lowest);
        for (std::size_t p = 0; p < want.size(); ++p) {
          const std::size_t from = std::max(p, static_cast<std::size_t>(lowest));
          EXPECT_EQ(partial[p].error, got[from].error) << "plane " << p << ", errors from " << lowest;
          EXPECT_EQ(partial[p].magnitude_bits, got[p].magnitude_bits) << "plane " << p;
        }
      }
    }
  }
}

}  // namespace
