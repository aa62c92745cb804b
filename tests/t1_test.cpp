// Tier-1 block coder (T.800 Annexes C and D): the MQ coder against the published ITU-T T.88
// Annex H.2 test sequence and an independent MQ decoder; whole code-blocks against an independent
// tier-1 decoder (t1_reference_decoder.h) for every orientation, many sizes, coefficient
// distributions and every code-block style switch; every pass's truncation length and distortion
// figure checked by decoding the truncated codeword.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/t1/block_encoder.h"
#include "codec/t1/block_style.h"
#include "codec/t1/mq_encoder.h"
#include "t1_reference_decoder.h"

namespace {

using codec::t1::BlockStyle;
using codec::t1::EncodedBlock;
using codec::t1::MqContext;
using codec::t1::MqEncoder;
using codec::t1::Orientation;

// ---------------------------------------------------------------------------------------------
// MQ coder

// ITU-T T.88 (JBIG2) Annex H.2: 256 decisions (32 bytes, MSB first) coded in a single context
// starting at state 0, MPS 0; JBIG2's MQ coder is the one of T.800 Annex C.
const std::vector<std::uint8_t> kT88Decisions = {0x00, 0x02, 0x00, 0x51, 0x00, 0x00, 0x00, 0xC0, 0x03, 0x52, 0x87,
                                                 0x2A, 0xAA, 0xAA, 0xAA, 0xAA, 0x82, 0xC0, 0x20, 0x00, 0xFC, 0xD7,
                                                 0x9E, 0xF6, 0xBF, 0x7F, 0xED, 0x90, 0x4F, 0x46, 0xA3, 0xBF};
const std::vector<std::uint8_t> kT88Coded = {0x84, 0xC7, 0x3B, 0xFC, 0xE1, 0xA1, 0x43, 0x04, 0x02, 0x20,
                                             0x00, 0x00, 0x41, 0x0D, 0xBB, 0x86, 0xF4, 0x31, 0x7F, 0xFF,
                                             0x88, 0xFF, 0x37, 0x47, 0x1A, 0xDB, 0x6A, 0xDF, 0xFF, 0xAC};

int t88_decision(int i) { return (kT88Decisions[static_cast<std::size_t>(i / 8)] >> (7 - i % 8)) & 1; }

TEST(MqCoder, MatchesT88AnnexH2TestSequence) {
  std::vector<std::uint8_t> out;
  MqEncoder mq(out);
  mq.start();
  MqContext cx;
  for (int i = 0; i < 256; ++i) mq.encode(t88_decision(i), cx);
  mq.flush();
  // T.88's flush keeps the final 0xFF of the second BYTEOUT and appends 0xAC (the 0xFFAC end
  // marker of JBIG2); T.800's codeword drops that final 0xFF, which the decoder's 0xFF fill
  // supplies anyway. Everything before it must agree byte for byte.
  const std::vector<std::uint8_t> expected(kT88Coded.begin(), kT88Coded.end() - 2);
  EXPECT_EQ(out, expected);

  const std::vector<std::uint8_t>* streams[] = {&out, &kT88Coded};
  for (const auto* stream : streams) {
    t1ref::MqDecoder dec(*stream);
    t1ref::RefContext rc;
    int wrong = 0;
    for (int i = 0; i < 256; ++i) wrong += dec.decode(rc) != t88_decision(i);
    EXPECT_EQ(wrong, 0);
  }
}

struct Symbol {
  int bit;
  int context;
};

// Decisions in several contexts with skews from fair to extreme, so that long MPS runs, carries
// and 0xFF bytes all occur.
std::vector<Symbol> random_symbols(std::mt19937& rng, int n, int contexts) {
  std::vector<double> p_one(static_cast<std::size_t>(contexts));
  for (int c = 0; c < contexts; ++c) p_one[static_cast<std::size_t>(c)] = std::pow(0.5, c % 9) * (c % 2 ? 1.0 : 0.5);
  std::uniform_int_distribution<int> pick(0, contexts - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Symbol> s(static_cast<std::size_t>(n));
  for (auto& sym : s) {
    sym.context = pick(rng);
    const double p = p_one[static_cast<std::size_t>(sym.context)];
    sym.bit = u(rng) < (sym.context % 3 == 0 ? 1.0 - p : p) ? 1 : 0;
  }
  return s;
}

int count_decode_errors(std::span<const std::uint8_t> data, const std::vector<Symbol>& symbols, std::size_t n,
                        int contexts) {
  t1ref::MqDecoder dec(data);
  std::vector<t1ref::RefContext> cx(static_cast<std::size_t>(contexts));
  int wrong = 0;
  for (std::size_t i = 0; i < n; ++i)
    wrong += dec.decode(cx[static_cast<std::size_t>(symbols[i].context)]) != symbols[i].bit;
  return wrong;
}

TEST(MqCoder, RandomSequencesDecodeIndependentlyWithBothTerminations) {
  for (int predictable = 0; predictable < 2; ++predictable)
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
      std::mt19937 rng(seed);
      const int contexts = 1 + static_cast<int>(seed % 7) * 3;
      const auto symbols = random_symbols(rng, 1 + static_cast<int>(seed * seed * 731 % 40000), contexts);
      std::vector<std::uint8_t> out;
      MqEncoder mq(out);
      mq.start();
      std::vector<MqContext> cx(static_cast<std::size_t>(contexts));
      for (const Symbol& s : symbols) mq.encode(s.bit, cx[static_cast<std::size_t>(s.context)]);
      predictable ? mq.flush_predictable() : mq.flush();
      ASSERT_FALSE(!out.empty() && out.back() == 0xFF);
      EXPECT_EQ(count_decode_errors(out, symbols, symbols.size(), contexts), 0)
          << "seed " << seed << " predictable " << predictable;
    }
}

// encode_zeros(cx, n) codes runs of zeros in one step where it can; the codeword must be the one
// n separate encode(0, cx) calls give, whatever the context's state and sense (zero as MPS or LPS)
// and however runs and single symbols interleave.
TEST(MqCoder, ZeroRunsCodeAsSingleSymbolsDo) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> batched, single;
    MqEncoder by_runs(batched), by_symbols(single);
    by_runs.start();
    by_symbols.start();
    std::vector<MqContext> cx_runs(3), cx_symbols(3);
    const int skew = static_cast<int>(seed % 4);  // how often a 1 breaks the runs
    for (int k = 0; k < 2000; ++k) {
      const std::size_t c = rng() % 3;
      if (static_cast<int>(rng() % 8) < skew) {
        by_runs.encode(1, cx_runs[c]);
        by_symbols.encode(1, cx_symbols[c]);
        continue;
      }
      const int run = 1 + static_cast<int>(rng() % (seed % 5 == 0 ? 5000 : 60));
      by_runs.encode_zeros(cx_runs[c], run);
      for (int i = 0; i < run; ++i) by_symbols.encode(0, cx_symbols[c]);
      ASSERT_EQ(cx_runs[c].packed, cx_symbols[c].packed) << "seed " << seed << " symbol " << k;
    }
    by_runs.flush();
    by_symbols.flush();
    EXPECT_EQ(batched, single) << "seed " << seed;
  }
}

// The truncation length reported for a point inside a segment must let a decoder that sees only
// that many bytes decode every symbol before the point.
TEST(MqCoder, TruncationLengthsAreSafe) {
  for (std::uint32_t seed = 100; seed < 130; ++seed) {
    std::mt19937 rng(seed);
    const int contexts = 1 + static_cast<int>(seed % 5) * 4;
    const auto symbols = random_symbols(rng, 6000, contexts);
    std::vector<std::uint8_t> out;
    MqEncoder mq(out);
    mq.start();
    std::vector<MqContext> cx(static_cast<std::size_t>(contexts));
    std::vector<std::pair<std::size_t, codec::t1::MqTruncationPoint>> points;
    for (std::size_t i = 0; i < symbols.size(); ++i) {
      mq.encode(symbols[i].bit, cx[static_cast<std::size_t>(symbols[i].context)]);
      if (i % 37 == 0 || i < 40) points.emplace_back(i + 1, mq.truncation_point());
    }
    seed % 2 ? mq.flush_predictable() : mq.flush();
    std::size_t previous = 0;
    for (const auto& [n, point] : points) {
      const std::size_t length = codec::t1::safe_truncation_length(out, point, out.size());
      ASSERT_LE(length, out.size());
      ASSERT_GE(length, previous);
      previous = length;
      const std::span<const std::uint8_t> cut(out.data(), length);
      ASSERT_EQ(count_decode_errors(cut, symbols, n, contexts), 0)
          << "seed " << seed << " after " << n << " symbols, " << length << " of " << out.size() << " bytes";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Code-block style

TEST(BlockStyleTest, SpcodRoundTrip) {
  for (int bits = 0; bits < 64; ++bits) {
    const auto b = static_cast<std::uint8_t>(bits);
    const BlockStyle s = BlockStyle::from_spcod(b);
    EXPECT_EQ(s.to_spcod(), b);
    EXPECT_EQ(BlockStyle::from_spcod(static_cast<std::uint8_t>(b | 0xC0)), s);  // bits 6, 7 are not tier-1 switches
  }
  EXPECT_TRUE(BlockStyle::from_spcod(0x01).bypass);
  EXPECT_TRUE(BlockStyle::from_spcod(0x02).reset);
  EXPECT_TRUE(BlockStyle::from_spcod(0x04).terminate_each_pass);
  EXPECT_TRUE(BlockStyle::from_spcod(0x08).vertically_causal);
  EXPECT_TRUE(BlockStyle::from_spcod(0x10).predictable_termination);
  EXPECT_TRUE(BlockStyle::from_spcod(0x20).segmentation_symbols);
  EXPECT_EQ(BlockStyle{}.to_spcod(), 0);
}

// ---------------------------------------------------------------------------------------------
// Code-blocks against the reference decoder

enum class Dist { Zero, Single, Sparse, Dense, Laplacian, Large, Huge };

const char* dist_name(Dist d) {
  switch (d) {
    case Dist::Zero:
      return "zero";
    case Dist::Single:
      return "single";
    case Dist::Sparse:
      return "sparse";
    case Dist::Dense:
      return "dense";
    case Dist::Laplacian:
      return "laplacian";
    case Dist::Large:
      return "large";
    case Dist::Huge:
      return "huge";
  }
  return "?";
}

struct Block {
  std::vector<std::int32_t> c;
  int mb;  // Mb given to the encoder: enough planes, sometimes a few more (missing MSBs)
};

Block make_block(Dist d, int w, int h, std::mt19937& rng) {
  const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  Block b{std::vector<std::int32_t>(n, 0), 0};
  std::uniform_int_distribution<int> coin(0, 1);
  auto signed_value = [&](std::int64_t magnitude) {
    return static_cast<std::int32_t>(coin(rng) ? -magnitude : magnitude);
  };
  auto magnitude_below = [&](std::int64_t limit) {
    return std::uniform_int_distribution<std::int64_t>(0, limit - 1)(rng);
  };
  switch (d) {
    case Dist::Zero:
      break;
    case Dist::Single:
      b.c[std::uniform_int_distribution<std::size_t>(0, n - 1)(rng)] = signed_value(1 + magnitude_below(4095));
      break;
    case Dist::Sparse:
      for (auto& v : b.c)
        if (std::uniform_int_distribution<int>(0, 9)(rng) == 0) v = signed_value(1 + magnitude_below(999));
      break;
    case Dist::Dense:
      for (auto& v : b.c) v = signed_value(magnitude_below(256));
      break;
    case Dist::Laplacian: {
      std::exponential_distribution<double> e(1.0 / 12.0);
      for (auto& v : b.c) v = signed_value(std::min<std::int64_t>(static_cast<std::int64_t>(e(rng)), 65535));
      break;
    }
    case Dist::Large:  // magnitudes up to 2^20
      for (auto& v : b.c) v = signed_value(magnitude_below((std::int64_t{1} << 20) + 1));
      break;
    case Dist::Huge:  // up to 2^31 - 1, the most Mb = 31 allows
      for (auto& v : b.c) v = signed_value(magnitude_below(std::int64_t{1} << 31));
      b.c[0] = 2147483647;
      break;
  }
  std::uint32_t any = 0;
  for (auto v : b.c) any |= static_cast<std::uint32_t>(v < 0 ? -static_cast<std::int64_t>(v) : v);
  const int planes = static_cast<int>(std::bit_width(any));
  b.mb = std::min(31, planes + std::uniform_int_distribution<int>(0, 2)(rng));
  return b;
}

t1ref::Band band_of(Orientation o) {
  switch (o) {
    case Orientation::LL:
      return t1ref::Band::LL;
    case Orientation::HL:
      return t1ref::Band::HL;
    case Orientation::LH:
      return t1ref::Band::LH;
    case Orientation::HH:
      return t1ref::Band::HH;
  }
  return t1ref::Band::LL;
}

// Squared error on the integer grid, in long double: each term is exact, the sum near enough.
long double squared_error(const std::vector<std::int32_t>& c, const std::vector<std::int64_t>& r) {
  long double e = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const auto d = static_cast<long double>(static_cast<std::int64_t>(c[i]) - r[i]);
    e += d * d;
  }
  return e;
}

// No marker code (0xFF followed by 0x90..0xFF) anywhere, and no trailing 0xFF.
bool marker_free(const std::vector<std::uint8_t>& d) {
  for (std::size_t i = 0; i + 1 < d.size(); ++i)
    if (d[i] == 0xFF && d[i + 1] > 0x8F) return false;
  return d.empty() || d.back() != 0xFF;
}

std::string describe(int w, int h, Orientation o, Dist d, BlockStyle s) {
  std::ostringstream os;
  os << w << "x" << h << " orientation " << static_cast<int>(o) << " " << dist_name(d) << " style 0x" << std::hex
     << static_cast<int>(s.to_spcod());
  return os.str();
}

// Encodes, then decodes the whole codeword and every truncation of it at the reported pass lengths.
void check_block(const Block& b, int w, int h, Orientation o, BlockStyle style, const std::string& what) {
  SCOPED_TRACE(what);
  const EncodedBlock enc = codec::t1::encode_block(b.c, w, h, o, b.mb, style);

  std::uint32_t any = 0;
  for (auto v : b.c) any |= static_cast<std::uint32_t>(v < 0 ? -static_cast<std::int64_t>(v) : v);
  const int planes = static_cast<int>(std::bit_width(any));
  ASSERT_EQ(enc.missing_msbs, b.mb - planes);
  const int total = planes > 0 ? 3 * planes - 2 : 0;
  ASSERT_EQ(static_cast<int>(enc.passes.size()), total);
  if (total == 0) {
    EXPECT_TRUE(enc.data.empty());
    return;
  }
  ASSERT_EQ(enc.passes.back().length, enc.data.size());
  EXPECT_TRUE(marker_free(enc.data));

  // The decoder needs the segment lengths a packet header would carry: those of terminated passes.
  const t1ref::T1Decoder rules(w, h, band_of(o), planes, style, enc.data, {});
  std::vector<std::size_t> full_ends;
  for (int k = 0; k < total; ++k) {
    const auto& p = enc.passes[static_cast<std::size_t>(k)];
    ASSERT_EQ(p.terminated, rules.is_terminated(k)) << "pass " << k;
    if (k > 0) {
      ASSERT_GE(p.length, enc.passes[static_cast<std::size_t>(k - 1)].length) << "pass " << k;
    }
    if (p.terminated) full_ends.push_back(p.length);
  }

  // Full decode, remembering the reconstruction after every pass.
  std::vector<std::vector<std::int64_t>> after_pass;
  t1ref::T1Decoder full(w, h, band_of(o), planes, style, enc.data, full_ends);
  for (int k = 0; k < total; ++k) {
    full.decode_pass();
    after_pass.push_back(full.reconstruction());
  }
  EXPECT_EQ(full.segmentation_errors(), 0);
  std::vector<std::int64_t> original(b.c.begin(), b.c.end());
  ASSERT_EQ(after_pass.back(), original) << "lossless round trip";

  // Every truncation point: same reconstruction as the full decode, distortion as reported.
  const long double energy = squared_error(b.c, std::vector<std::int64_t>(b.c.size(), 0));
  // Every figure is an integer; below 2^50 all of them and their sums are exact in a double, so
  // the bookkeeping must then agree exactly. Above, within 1e-6 of the block's energy.
  const double tolerance = energy < 0x1p50L ? 0.5 : 1e-6 * static_cast<double>(energy);
  long double claimed = energy;
  for (int k = 1; k <= total; ++k) {
    const auto& last = enc.passes[static_cast<std::size_t>(k - 1)];
    claimed -= last.distortion_decrease;
    std::vector<std::size_t> ends;
    for (int j = 0; j < k - 1; ++j)
      if (enc.passes[static_cast<std::size_t>(j)].terminated)
        ends.push_back(enc.passes[static_cast<std::size_t>(j)].length);
    ends.push_back(last.length);
    const std::span<const std::uint8_t> cut(enc.data.data(), last.length);
    t1ref::T1Decoder dec(w, h, band_of(o), planes, style, cut, ends);
    for (int j = 0; j < k; ++j) dec.decode_pass();
    const auto recon = dec.reconstruction();
    ASSERT_EQ(recon, after_pass[static_cast<std::size_t>(k - 1)])
        << "truncated after pass " << k - 1 << " at " << last.length << " of " << enc.data.size() << " bytes";
    const long double error = squared_error(b.c, recon);
    ASSERT_LE(std::fabs(static_cast<double>(error - claimed)), tolerance)
        << "pass " << k - 1 << ": error " << static_cast<double>(error) << ", energy minus reported decreases "
        << static_cast<double>(claimed);
  }
}

const Orientation kOrientations[] = {Orientation::LL, Orientation::HL, Orientation::LH, Orientation::HH};

struct Size {
  int w, h;
};

std::vector<Size> all_sizes() {
  std::vector<Size> s;
  for (int w = 4; w <= 64; w *= 2)
    for (int h = 4; h <= 64; h *= 2) s.push_back({w, h});
  for (Size extra :
       {Size{32, 128}, Size{128, 32}, Size{1024, 4}, Size{4, 1024}, Size{1, 1}, Size{3, 5}, Size{7, 64}, Size{64, 7},
        Size{5, 3}, Size{2, 2}, Size{1, 9}, Size{13, 17}, Size{1024, 1}, Size{1, 1024}, Size{61, 3}})
    s.push_back(extra);
  return s;
}

TEST(T1, AllZeroBlockHasNoPasses) {
  const std::vector<std::int32_t> zeros(64 * 64, 0);
  const EncodedBlock enc = codec::t1::encode_block(zeros, 64, 64, Orientation::HH, 11, BlockStyle{});
  EXPECT_TRUE(enc.data.empty());
  EXPECT_TRUE(enc.passes.empty());
  EXPECT_EQ(enc.missing_msbs, 11);
}

TEST(T1, SinglePlaneBlockHasOneCleanupPass) {
  std::vector<std::int32_t> c(16, 0);
  c[5] = -1;
  const EncodedBlock enc = codec::t1::encode_block(c, 4, 4, Orientation::LL, 3, BlockStyle{});
  ASSERT_EQ(enc.passes.size(), 1u);
  EXPECT_EQ(enc.missing_msbs, 2);
  EXPECT_TRUE(enc.passes[0].terminated);
  EXPECT_DOUBLE_EQ(enc.passes[0].distortion_decrease, 1.0);
}

TEST(T1, RoundTripsEverySizeOrientationAndDistribution) {
  std::mt19937 rng(2024);
  for (Size s : all_sizes())
    for (Orientation o : kOrientations)
      for (Dist d : {Dist::Zero, Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian}) {
        const Block b = make_block(d, s.w, s.h, rng);
        check_block(b, s.w, s.h, o, BlockStyle{}, describe(s.w, s.h, o, d, BlockStyle{}));
        if (HasFatalFailure()) return;
      }
}

std::vector<BlockStyle> styles() {
  std::vector<BlockStyle> out;
  for (std::uint8_t bits : {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x20, 0x3F, 0x05, 0x11, 0x15, 0x29, 0x0B})
    out.push_back(BlockStyle::from_spcod(bits));
  return out;
}

// Checking every truncation point costs passes^2 * coefficients in the reference decoder, so the
// largest blocks take one orientation per case, rotating, while small ones take all four.
std::vector<Orientation> orientations_for(Size s, std::size_t rotation) {
  if (s.w * s.h <= 1024) return {std::begin(kOrientations), std::end(kOrientations)};
  return {kOrientations[rotation % 4]};
}

TEST(T1, RoundTripsEveryModeSwitchAloneAndTogether) {
  std::mt19937 rng(77);
  const Size sizes[] = {{4, 4}, {1, 1}, {3, 5}, {16, 16}, {7, 64}, {13, 17}, {64, 64}, {1024, 4}, {4, 1024}, {32, 128}};
  std::size_t rotation = 0;
  for (BlockStyle st : styles())
    for (Size s : sizes)
      for (Dist d : {Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian})
        for (Orientation o : orientations_for(s, rotation++)) {
          const Block b = make_block(d, s.w, s.h, rng);
          check_block(b, s.w, s.h, o, st, describe(s.w, s.h, o, d, st));
          if (HasFatalFailure()) return;
        }
}

TEST(T1, RoundTripsLargeMagnitudes) {
  std::mt19937 rng(31);
  const Size sizes[] = {{4, 4}, {3, 5}, {16, 16}, {64, 64}, {1024, 4}};
  std::size_t rotation = 0;
  for (BlockStyle st :
       {BlockStyle{}, BlockStyle::from_spcod(0x01), BlockStyle::from_spcod(0x3F), BlockStyle::from_spcod(0x19)})
    for (Size s : sizes)
      for (Dist d : {Dist::Large, Dist::Huge})
        for (Orientation o : orientations_for(s, rotation++)) {
          const Block b = make_block(d, s.w, s.h, rng);
          check_block(b, s.w, s.h, o, st, describe(s.w, s.h, o, d, st));
          if (HasFatalFailure()) return;
        }
}

TEST(T1, RejectsInconsistentArguments) {
  const std::vector<std::int32_t> c(12, 3);
  EXPECT_THROW(codec::t1::encode_block(c, 4, 4, Orientation::LL, 8, {}), std::invalid_argument);  // 12 != 16
  EXPECT_THROW(codec::t1::encode_block(c, 0, 12, Orientation::LL, 8, {}), std::invalid_argument);
  EXPECT_THROW(codec::t1::encode_block(c, 4, 3, Orientation::LL, 1, {}), std::invalid_argument);  // 3 needs 2 planes
  EXPECT_THROW(codec::t1::encode_block(c, 4, 3, Orientation::LL, 32, {}), std::invalid_argument);
  const std::vector<std::int32_t> lowest(1, INT32_MIN);  // magnitude 2^31 needs 32 planes
  EXPECT_THROW(codec::t1::encode_block(lowest, 1, 1, Orientation::LL, 31, {}), std::invalid_argument);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Reconstruction after truncation (codec/t1/reconstruction.h), against the reference decoder.

#include "codec/t1/reconstruction.h"

namespace {

using codec::t1::reconstruct;

std::vector<float> reconstructed(const Block& b, int w, int h, Orientation o, BlockStyle style, int passes,
                                 float final_offset) {
  std::vector<float> out(b.c.size(), -12345.0f);  // reconstruct() must overwrite every value
  reconstruct(b.c, w, h, o, b.mb, style, passes, out, final_offset);
  return out;
}

// What the reference decoder reconstructs from the codeword cut after pass k - 1 (at that pass's
// reported length), given the segment lengths a packet header would carry.
std::vector<std::int64_t> reference_after(const EncodedBlock& enc, int w, int h, Orientation o, int planes,
                                          BlockStyle style, int k) {
  if (k == 0) return std::vector<std::int64_t>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  const auto& last = enc.passes[static_cast<std::size_t>(k - 1)];
  std::vector<std::size_t> ends;
  for (int j = 0; j < k - 1; ++j)
    if (enc.passes[static_cast<std::size_t>(j)].terminated)
      ends.push_back(enc.passes[static_cast<std::size_t>(j)].length);
  ends.push_back(last.length);
  const std::span<const std::uint8_t> cut(enc.data.data(), last.length);
  t1ref::T1Decoder dec(w, h, band_of(o), planes, style, cut, ends);
  for (int j = 0; j < k; ++j) dec.decode_pass();
  return dec.reconstruction();
}

// For every truncation k = 0 .. passes: reconstruct() equals the reference decoder's mid-point
// reconstruction. That decoder reconstructs fully known magnitudes exactly, i.e. final_offset 0;
// with final_offset 0.5 every coefficient known down to plane 0 must move 0.5 away from zero and
// nothing else change. Which ones know plane 0 follows from the last pass received: none unless
// it is a pass of plane 0; after plane 0's refinement or cleanup pass every significant one; after
// its significance pass those it coded, which are exactly those reconstructed at magnitude 1
// (anything significant before plane 0 reconstructs at an odd magnitude >= 3). Also: the squared
// error with final_offset 0 is the energy minus the reported distortion decreases.
void check_reconstruction(const Block& b, int w, int h, Orientation o, BlockStyle style, const std::string& what) {
  SCOPED_TRACE(what);
  const EncodedBlock enc = codec::t1::encode_block(b.c, w, h, o, b.mb, style);
  const int planes = b.mb - enc.missing_msbs;
  const int total = static_cast<int>(enc.passes.size());
  const t1ref::T1Decoder rules(w, h, band_of(o), planes, style, enc.data, {});
  const long double energy = squared_error(b.c, std::vector<std::int64_t>(b.c.size(), 0));
  const double tolerance = 1e-6 * static_cast<double>(energy);
  long double claimed = energy;
  for (int k = 0; k <= total; ++k) {
    if (k > 0) claimed -= enc.passes[static_cast<std::size_t>(k - 1)].distortion_decrease;
    const std::vector<std::int64_t> ref = reference_after(enc, w, h, o, planes, style, k);
    const std::vector<float> exact = reconstructed(b, w, h, o, style, k, 0.0f);
    const std::vector<float> offset = reconstructed(b, w, h, o, style, k, 0.5f);
    const bool plane0 = k > 0 && rules.plane_of(k - 1) == 0;
    const bool plane0_spp = plane0 && t1ref::T1Decoder::kind_of(k - 1) == 0;
    long double error = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
      const std::int64_t r = ref[i];
      ASSERT_EQ(exact[i], static_cast<float>(r))
          << "final_offset 0, after " << k << " of " << total << " passes, coefficient "
          << i % static_cast<std::size_t>(w) << "," << i / static_cast<std::size_t>(w) << " = " << b.c[i];
      const bool knows_plane0 = r != 0 && plane0 && (!plane0_spp || r == 1 || r == -1);
      const double shifted = static_cast<double>(r) + (knows_plane0 ? (r < 0 ? -0.5 : 0.5) : 0.0);
      ASSERT_EQ(offset[i], static_cast<float>(shifted))
          << "final_offset 0.5, after " << k << " of " << total << " passes, coefficient "
          << i % static_cast<std::size_t>(w) << "," << i / static_cast<std::size_t>(w) << " = " << b.c[i];
      const long double d = static_cast<long double>(b.c[i]) - static_cast<long double>(exact[i]);
      error += d * d;
    }
    ASSERT_LE(std::fabs(static_cast<double>(error - claimed)), tolerance)
        << "after " << k << " passes: error " << static_cast<double>(error) << ", energy minus reported decreases "
        << static_cast<double>(claimed);
  }
  // More passes than the block has: everything received.
  EXPECT_EQ(reconstructed(b, w, h, o, style, total + 5, 0.5f), reconstructed(b, w, h, o, style, total, 0.5f));
}

TEST(T1Reconstruction, MatchesReferenceDecoderAtEveryTruncation) {
  std::mt19937 rng(4242);
  const Size sizes[] = {{1, 1}, {3, 5}, {4, 4}, {2, 9}, {13, 17}, {16, 16}, {7, 64}, {64, 7}, {64, 64}};
  std::size_t rotation = 0;
  for (BlockStyle st : styles())
    for (Size s : sizes)
      for (Dist d : {Dist::Zero, Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian})
        for (Orientation o : orientations_for(s, rotation++)) {
          const Block b = make_block(d, s.w, s.h, rng);
          check_reconstruction(b, s.w, s.h, o, st, describe(s.w, s.h, o, d, st));
          if (HasFatalFailure()) return;
        }
}

TEST(T1Reconstruction, MatchesReferenceDecoderForLargeMagnitudes) {
  std::mt19937 rng(99);
  const Size sizes[] = {{3, 5}, {16, 16}, {64, 64}};
  std::size_t rotation = 0;
  for (BlockStyle st :
       {BlockStyle{}, BlockStyle::from_spcod(0x01), BlockStyle::from_spcod(0x08), BlockStyle::from_spcod(0x3F)})
    for (Size s : sizes)
      for (Dist d : {Dist::Large, Dist::Huge})
        for (Orientation o : orientations_for(s, rotation++)) {
          const Block b = make_block(d, s.w, s.h, rng);
          check_reconstruction(b, s.w, s.h, o, st, describe(s.w, s.h, o, d, st));
          if (HasFatalFailure()) return;
        }
}

// Irreversible coding hands tier-1 each coefficient's fraction below its index. The codeword must
// not change, and each pass's reported decrease must then be the true one against the coefficient
// itself (index + fraction / 256) for a decoder placing fully known magnitudes at index + 1/2:
// energy minus the decreases so far equals the squared error of reconstruct(..., 0.5) against the
// real values, at every truncation. Large magnitudes too, where fewer fraction bits fit.
TEST(T1Reconstruction, FractionsMakeDistortionExactAgainstTheCoefficient) {
  std::mt19937 rng(7);
  const Size sizes[] = {{1, 1}, {5, 3}, {16, 16}, {64, 64}};
  std::size_t rotation = 0;
  for (BlockStyle st : {BlockStyle{}, BlockStyle::from_spcod(0x01), BlockStyle::from_spcod(0x08)})
    for (Size s : sizes)
      for (Dist d : {Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian, Dist::Large, Dist::Huge})
        for (Orientation o : orientations_for(s, rotation++)) {
          SCOPED_TRACE(describe(s.w, s.h, o, d, st));
          const Block b = make_block(d, s.w, s.h, rng);
          std::vector<std::uint8_t> fractions(b.c.size());
          for (auto& f : fractions) f = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(rng));
          const EncodedBlock plain = codec::t1::encode_block(b.c, s.w, s.h, o, b.mb, st);
          const EncodedBlock enc = codec::t1::encode_block(b.c, s.w, s.h, o, b.mb, st, fractions);
          ASSERT_EQ(enc.data, plain.data);
          ASSERT_EQ(enc.passes.size(), plain.passes.size());
          // The fixed point keeps 31 - planes fraction bits, at most 8: the values the encoder saw.
          const int planes = b.mb - enc.missing_msbs;
          const int kept = std::clamp(31 - planes, 0, 8);
          std::vector<long double> real(b.c.size());
          long double energy = 0;
          for (std::size_t i = 0; i < real.size(); ++i) {
            const long double m = std::fabs(static_cast<long double>(b.c[i])) +
                                  std::ldexp(static_cast<long double>(fractions[i] >> (8 - kept)), -kept);
            real[i] = b.c[i] < 0 ? -m : m;
            energy += m * m;
          }
          ASSERT_NEAR(static_cast<double>(energy), enc.energy, 1e-9 * static_cast<double>(energy) + 1e-9);
          long double claimed = energy;
          for (int k = 0; k <= static_cast<int>(enc.passes.size()); ++k) {
            if (k > 0) claimed -= enc.passes[static_cast<std::size_t>(k - 1)].distortion_decrease;
            std::vector<float> out(b.c.size());
            codec::t1::reconstruct(b.c, s.w, s.h, o, b.mb, st, k, out, 0.5f);
            long double error = 0;
            for (std::size_t i = 0; i < out.size(); ++i) {
              const long double e = real[i] - static_cast<long double>(out[i]);
              error += e * e;
            }
            ASSERT_LE(std::fabs(static_cast<double>(error - claimed)), 1e-6 * static_cast<double>(energy) + 1e-6)
                << "after " << k << " passes";
          }
        }
}

// The scan order and the neighbourhood, worked by hand. One column of eight (two stripes), three
// planes: passes 0 cleanup (plane 2), 1-3 plane 1, 4 significance propagation of plane 0.
TEST(T1Reconstruction, SignificancePropagatesInScanOrderOnly) {
  const Block b{{0, 0, 1, 1, 4, 1, 0, 0}, 3};
  // 4 (known down to plane 1) reconstructs at 5. Row 2 comes before row 3 in the scan and has no
  // significant neighbour then; row 3 has 4 below; row 5 has 4 above.
  EXPECT_EQ(reconstructed(b, 1, 8, Orientation::LL, {}, 5, 0.5f), (std::vector<float>{0, 0, 0, 1.5f, 5, 1.5f, 0, 0}));
  // Vertically causal: row 3, last of its stripe, does not see the stripe below.
  const BlockStyle causal = BlockStyle::from_spcod(0x08);
  EXPECT_EQ(reconstructed(b, 1, 8, Orientation::LL, causal, 5, 0.5f), (std::vector<float>{0, 0, 0, 0, 5, 1.5f, 0, 0}));
  // The refinement pass of plane 0 then fixes 4; the cleanup pass codes the rest.
  EXPECT_EQ(reconstructed(b, 1, 8, Orientation::LL, causal, 6, 0.5f),
            (std::vector<float>{0, 0, 0, 0, 4.5f, 1.5f, 0, 0}));
  EXPECT_EQ(reconstructed(b, 1, 8, Orientation::LL, causal, 7, 0.0f), (std::vector<float>{0, 0, 1, 1, 4, 1, 0, 0}));
  // Along a row, within a stripe: newly significant coefficients propagate to the right only.
  const Block row{{1, 1, 1, 4, 1, 1}, 3};
  EXPECT_EQ(reconstructed(row, 6, 1, Orientation::HH, {}, 5, 0.5f), (std::vector<float>{0, 0, 1.5f, 5, 1.5f, 1.5f}));
  // Before plane 0: after the cleanup pass of plane 2, 4 lies in [4, 8) and reconstructs at 6;
  // after plane 1's significance pass still so; nothing else is significant.
  EXPECT_EQ(reconstructed(row, 6, 1, Orientation::HH, {}, 1, 0.5f), (std::vector<float>{0, 0, 0, 6, 0, 0}));
  EXPECT_EQ(reconstructed(row, 6, 1, Orientation::HH, {}, 2, 0.5f), (std::vector<float>{0, 0, 0, 6, 0, 0}));
  EXPECT_EQ(reconstructed(row, 6, 1, Orientation::HH, {}, 0, 0.5f), (std::vector<float>(6, 0.0f)));
  const Block negative{{-3}, 2};
  EXPECT_EQ(reconstructed(negative, 1, 1, Orientation::LL, {}, 1, 0.5f), (std::vector<float>{-3}));
  EXPECT_EQ(reconstructed(negative, 1, 1, Orientation::LL, {}, 4, 0.5f), (std::vector<float>{-3.5f}));
  EXPECT_EQ(reconstructed(negative, 1, 1, Orientation::LL, {}, 4, 0.0f), (std::vector<float>{-3}));
}

TEST(T1Reconstruction, RejectsInconsistentArguments) {
  const std::vector<std::int32_t> c(12, 3);
  std::vector<float> out(12);
  std::vector<float> short_out(11);
  EXPECT_NO_THROW(reconstruct(c, 4, 3, Orientation::LL, 2, {}, 3, out));
  EXPECT_THROW(reconstruct(c, 4, 4, Orientation::LL, 8, {}, 3, out), std::invalid_argument);  // 12 != 16
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 8, {}, 3, short_out), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 0, 12, Orientation::LL, 8, {}, 3, out), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 1, {}, 3, out), std::invalid_argument);  // 3 needs 2 planes
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 32, {}, 3, out), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 8, {}, -1, out), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 8, {}, 3, out, 1.0f), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 8, {}, 3, out, -0.25f), std::invalid_argument);
  EXPECT_THROW(reconstruct(c, 4, 3, Orientation::LL, 8, {}, 3, out, std::nanf("")), std::invalid_argument);
  const std::vector<std::int32_t> lowest(1, INT32_MIN);
  std::vector<float> one(1);
  EXPECT_THROW(reconstruct(lowest, 1, 1, Orientation::LL, 31, {}, 1, one), std::invalid_argument);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Minimal truncation lengths: every non-terminated pass's length is the shortest one that still
// decodes. At the reported length everything up to the pass decodes right; one byte less (when
// that is not below the previous pass's length, which is itself minimal, or the segment's start)
// gets some decision wrong.

namespace {

// Decisions in a few contexts, in stretches of random length with their own skew, from fair to
// one LPS in thousands: long MPS runs drive the encoder's interval against its upper end, where
// it writes runs of 0xFF / 0x7F bytes that the decoder's 1-fill synthesises.
std::vector<Symbol> regime_symbols(std::mt19937& rng, int n, int contexts) {
  std::vector<Symbol> s;
  std::uniform_int_distribution<int> pick(0, contexts - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  while (static_cast<int>(s.size()) < n) {
    const int length = std::uniform_int_distribution<int>(1, 400)(rng);
    const double p_lps = std::pow(0.5, std::uniform_int_distribution<int>(1, 13)(rng));
    const int lps = std::uniform_int_distribution<int>(0, 1)(rng);
    const bool one_context = u(rng) < 0.5;
    const int fixed = pick(rng);
    for (int i = 0; i < length && static_cast<int>(s.size()) < n; ++i)
      s.push_back(Symbol{u(rng) < p_lps ? lps : 1 - lps, one_context ? fixed : pick(rng)});
  }
  return s;
}

TEST(MqCoder, MinimalTruncationLengthsAreExact) {
  long points = 0, shorter = 0, saved = 0, before_committed = 0, free_points = 0;
  for (std::uint32_t seed = 300; seed < 380; ++seed) {
    std::mt19937 rng(seed);
    const int contexts = 1 + static_cast<int>(seed % 4);
    const int n = 300 + static_cast<int>(seed * 7919 % 2500);
    const auto symbols = seed % 3 == 0 ? random_symbols(rng, n, contexts) : regime_symbols(rng, n, contexts);
    std::vector<std::uint8_t> out;
    MqEncoder mq(out);
    mq.start();
    std::vector<MqContext> cx(static_cast<std::size_t>(contexts));
    std::vector<codec::t1::MqTruncationPoint> after;  // after symbol i + 1
    for (const Symbol& s : symbols) {
      mq.encode(s.bit, cx[static_cast<std::size_t>(s.context)]);
      after.push_back(mq.truncation_point());
    }
    seed % 2 ? mq.flush_predictable() : mq.flush();
    std::size_t previous = 0;
    for (std::size_t i = 0; i < after.size(); ++i) {
      const auto& point = after[i];
      const std::size_t length = codec::t1::minimal_truncation_length(out, point, out.size(), previous);
      const std::size_t safe = codec::t1::safe_truncation_length(out, point, out.size());
      SCOPED_TRACE("seed " + std::to_string(seed) + " after " + std::to_string(i + 1) + " symbols, " +
                   std::to_string(length) + " of " + std::to_string(out.size()) + " bytes");
      ASSERT_GE(length, previous);
      ASSERT_LE(length, safe);
      ASSERT_TRUE(length == 0 || out[length - 1] != 0xFF);
      ASSERT_EQ(count_decode_errors(std::span(out.data(), length), symbols, i + 1, contexts), 0);
      if (length > previous) {
        ASSERT_GT(count_decode_errors(std::span(out.data(), length - 1), symbols, i + 1, contexts), 0);
      }
      ++points;
      shorter += length < safe;
      saved += static_cast<long>(safe - length);
      before_committed += length + 1 < point.committed;
      free_points += length == 0;
      previous = length;
    }
  }
  std::printf(
      "%ld points: %ld (%.1f%%) shorter than the safe length, %.3f bytes less on average; %ld cut more than "
      "one byte before the bytes committed; %ld need no byte\n",
      points, shorter, 100.0 * static_cast<double>(shorter) / static_cast<double>(points),
      static_cast<double>(saved) / static_cast<double>(points), before_committed, free_points);
  EXPECT_GT(before_committed, 0);  // the 1-fill run case is exercised
}

struct LengthStats {
  long passes = 0, checked_below = 0, empty = 0;
};

// Encodes, then decodes every non-terminated pass at its length and one byte less.
void check_minimal_lengths(const Block& b, int w, int h, Orientation o, BlockStyle style, const std::string& what,
                           LengthStats& stats) {
  SCOPED_TRACE(what);
  const EncodedBlock enc = codec::t1::encode_block(b.c, w, h, o, b.mb, style);
  const int planes = b.mb - enc.missing_msbs;
  const int total = static_cast<int>(enc.passes.size());
  if (total == 0) return;
  std::vector<std::size_t> full_ends;
  for (const auto& p : enc.passes)
    if (p.terminated) full_ends.push_back(p.length);
  std::vector<std::vector<std::int64_t>> after_pass;
  t1ref::T1Decoder full(w, h, band_of(o), planes, style, enc.data, full_ends);
  for (int k = 0; k < total; ++k) {
    full.decode_pass();
    after_pass.push_back(full.reconstruction());
  }
  ASSERT_EQ(full.segmentation_errors(), 0);

  // Decodes passes 0..k from the first `length` bytes; whether everything came out as in the full decode.
  auto decodes_right = [&](int k, std::size_t length) {
    std::vector<std::size_t> ends;
    for (int j = 0; j < k; ++j)
      if (enc.passes[static_cast<std::size_t>(j)].terminated)
        ends.push_back(enc.passes[static_cast<std::size_t>(j)].length);
    ends.push_back(length);
    t1ref::T1Decoder dec(w, h, band_of(o), planes, style, std::span(enc.data.data(), length), ends);
    for (int j = 0; j <= k; ++j) dec.decode_pass();
    return dec.segmentation_errors() == 0 && dec.reconstruction() == after_pass[static_cast<std::size_t>(k)];
  };
  for (int k = 0; k < total; ++k) {
    const auto& p = enc.passes[static_cast<std::size_t>(k)];
    if (p.terminated) continue;
    const std::size_t previous = k > 0 ? enc.passes[static_cast<std::size_t>(k - 1)].length : 0;
    ++stats.passes;
    ASSERT_TRUE(decodes_right(k, p.length)) << "pass " << k << " at " << p.length << " bytes";
    if (p.length == previous) {
      ++stats.empty;
      continue;
    }
    ++stats.checked_below;
    ASSERT_FALSE(decodes_right(k, p.length - 1)) << "pass " << k << " also decodes at " << p.length - 1 << " bytes";
  }
}

TEST(T1, TruncationLengthsAreMinimal) {
  std::mt19937 rng(5150);
  LengthStats stats;
  const Size sizes[] = {{4, 4}, {1, 1}, {3, 5}, {16, 16}, {7, 64}, {13, 17}, {32, 32}, {64, 64}, {256, 4}, {4, 256}};
  std::size_t rotation = 0;
  for (BlockStyle st : styles())
    for (Size s : sizes)
      for (Dist d : {Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian})
        for (Orientation o : orientations_for(s, rotation++)) {
          const Block b = make_block(d, s.w, s.h, rng);
          check_minimal_lengths(b, s.w, s.h, o, st, describe(s.w, s.h, o, d, st), stats);
          if (HasFatalFailure()) return;
        }
  for (BlockStyle st : {BlockStyle{}, BlockStyle::from_spcod(0x01), BlockStyle::from_spcod(0x3F)})
    for (Size s : {Size{16, 16}, Size{64, 64}})
      for (Dist d : {Dist::Large, Dist::Huge}) {
        const Block b = make_block(d, s.w, s.h, rng);
        check_minimal_lengths(b, s.w, s.h, Orientation::HH, st, describe(s.w, s.h, Orientation::HH, d, st), stats);
        if (HasFatalFailure()) return;
      }
  std::printf("%ld non-terminated passes: %ld checked one byte short, %ld add no byte to the previous pass\n",
              stats.passes, stats.checked_below, stats.empty);
  EXPECT_GT(stats.checked_below, 1000);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Bit-for-bit stability of the block coder. The digest below was recorded from the tier-1 coder
// as it stood before its speed rewrite (commit ec866bd) over every block of this test: every size
// of all_sizes() and a few more, every orientation, every distribution, every style of styles(),
// with and without fractions, orientations in rotation. Any change to a codeword byte, a pass's truncation length, its
// distortion figure (to the last bit of the double), the energy or the missing MSBs changes it.
// A faster coder must produce exactly the same; the round-trip tests above say the old one was
// right.

namespace {

struct Digest {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bits
  void bytes(const void* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h ^= static_cast<const std::uint8_t*>(p)[i];
      h *= 1099511628211ull;
    }
  }
  template <class T>
  void value(T v) {
    bytes(&v, sizeof v);
  }
};

void digest_block(Digest& dg, const EncodedBlock& e) {
  dg.value(e.data.size());
  dg.bytes(e.data.data(), e.data.size());
  dg.value(e.energy);
  dg.value(e.missing_msbs);
  dg.value(e.passes.size());
  for (const auto& p : e.passes) {
    dg.value(p.length);
    dg.value(p.distortion_decrease);
    dg.value(static_cast<int>(p.terminated));
  }
}

}  // namespace

TEST(T1Golden, EveryCodewordLengthAndDistortionAsRecorded) {
  std::mt19937 rng(9001);
  Digest dg;
  std::size_t blocks = 0;
  std::vector<Size> sizes = all_sizes();
  for (Size extra : {Size{64, 64}, Size{64, 64}, Size{32, 32}, Size{128, 16}, Size{16, 256}}) sizes.push_back(extra);
  for (BlockStyle st : styles())
    for (Size s : sizes)
      for (Dist d : {Dist::Zero, Dist::Single, Dist::Sparse, Dist::Dense, Dist::Laplacian, Dist::Large, Dist::Huge})
        for (bool with_fractions : {false, true}) {
          const Orientation o = kOrientations[blocks % 4];  // rotating: every one meets every case
          const Block b = make_block(d, s.w, s.h, rng);
          std::vector<std::uint8_t> fractions;
          if (with_fractions)
            for (std::size_t i = 0; i < b.c.size(); ++i)
              fractions.push_back(static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(rng)));
          digest_block(dg, codec::t1::encode_block(b.c, s.w, s.h, o, b.mb, st, fractions));
          ++blocks;
        }
  EXPECT_EQ(blocks, 8190u);
  EXPECT_EQ(dg.h, 0x782c1de8dce204c0ull) << std::hex << "digest 0x" << dg.h;
}

// ---------------------------------------------------------------------------------------------
// Blocks coded in place (IntegerBlock, FloatBlock) give exactly what the span entry point gives for
// the same indices (and, for floats, the indices and fractions dead_zone.h's quantize() makes).

#include "codec/t1/dead_zone.h"

TEST(T1InPlace, SameCodewordsAsFromCopiedIndices) {
  std::mt19937 rng(515);
  std::normal_distribution<float> coefficient(0.0f, 40.0f);
  const Size sizes[] = {{64, 64}, {1, 1}, {3, 5}, {13, 17}, {32, 8}, {4, 64}};
  for (BlockStyle st : {BlockStyle{}, BlockStyle::from_spcod(0x3F), BlockStyle::from_spcod(0x19)})
    for (Size s : sizes)
      for (Orientation o : kOrientations) {
        const int stride = s.w + 7;  // the block sits inside a wider plane, one row of margin above
        std::vector<float> plane(static_cast<std::size_t>(stride) * static_cast<std::size_t>(s.h + 1));
        for (float& v : plane)
          v = coefficient(rng) * (std::uniform_int_distribution<int>(0, 3)(rng) == 0 ? 8.0f : 1.0f);
        const float inverse_step = 1.0f / 0.37f;
        const float* origin = plane.data() + stride + 3;
        std::vector<std::int32_t> indices;
        std::vector<std::uint8_t> fractions;
        std::vector<std::int32_t> integer_plane(plane.size());
        for (int y = 0; y < s.h; ++y)
          for (int x = 0; x < s.w; ++x) {
            std::uint8_t f = 0;
            indices.push_back(codec::t1::quantize(origin[y * stride + x], inverse_step, f));
            fractions.push_back(f);
            integer_plane[static_cast<std::size_t>((y + 1) * stride + 3 + x)] = indices.back();
          }
        SCOPED_TRACE(describe(s.w, s.h, o, Dist::Dense, st));
        const EncodedBlock copied = codec::t1::encode_block(indices, s.w, s.h, o, 31, st, fractions);
        const EncodedBlock in_place =
            codec::t1::encode_block(codec::t1::FloatBlock{origin, stride, s.w, s.h, inverse_step}, o, 31, st);
        Digest a, b;
        digest_block(a, copied);
        digest_block(b, in_place);
        EXPECT_EQ(a.h, b.h);
        EXPECT_EQ(in_place.bit_planes, 31 - in_place.missing_msbs);
        const EncodedBlock exact = codec::t1::encode_block(indices, s.w, s.h, o, 31, st);
        const EncodedBlock exact_in_place = codec::t1::encode_block(
            codec::t1::IntegerBlock{integer_plane.data() + stride + 3, stride, s.w, s.h}, o, 31, st);
        Digest c, d;
        digest_block(c, exact);
        digest_block(d, exact_in_place);
        EXPECT_EQ(c.h, d.h);
        // Without the distortion bookkeeping: the same codeword, lengths and energy, every pass 0.
        for (const bool lossy : {true, false}) {
          const EncodedBlock& measured = lossy ? in_place : exact_in_place;
          const EncodedBlock skipped =
              lossy ? codec::t1::encode_block(codec::t1::FloatBlock{origin, stride, s.w, s.h, inverse_step}, o, 31, st,
                                              {}, codec::t1::Distortion::Skipped)
                    : codec::t1::encode_block(
                          codec::t1::IntegerBlock{integer_plane.data() + stride + 3, stride, s.w, s.h}, o, 31, st, {},
                          codec::t1::Distortion::Skipped);
          EXPECT_EQ(skipped.data, measured.data);
          EXPECT_EQ(skipped.energy, measured.energy);
          ASSERT_EQ(skipped.passes.size(), measured.passes.size());
          bool measured_something = false;
          for (std::size_t p = 0; p < skipped.passes.size(); ++p) {
            EXPECT_EQ(skipped.passes[p].length, measured.passes[p].length);
            EXPECT_EQ(skipped.passes[p].terminated, measured.passes[p].terminated);
            EXPECT_EQ(skipped.passes[p].distortion_decrease, 0.0);
            measured_something |= measured.passes[p].distortion_decrease != 0.0;
          }
          EXPECT_EQ(measured_something, !measured.passes.empty());
        }
      }
  const std::vector<std::int32_t> ones(16, 1);
  EXPECT_THROW(codec::t1::encode_block(codec::t1::IntegerBlock{ones.data(), 4, 4, 4}, Orientation::LL, 8, {},
                                       codec::t1::StopRule{1.0, 1.0}, codec::t1::Distortion::Skipped),
               std::invalid_argument);  // a stop rule needs the distortion
  EXPECT_THROW(codec::t1::encode_block(codec::t1::IntegerBlock{nullptr, 4, 4, 4}, Orientation::LL, 8, {}),
               std::invalid_argument);
  const std::vector<std::int32_t> row(4, 1);
  EXPECT_THROW(codec::t1::encode_block(codec::t1::IntegerBlock{row.data(), 2, 4, 1}, Orientation::LL, 8, {}),
               std::invalid_argument);  // rows narrower than the block
}

// The stop rule's block skip: a block whose whole energy, bought with one byte, is worth less than
// the stop slope gets no pass (and says it stopped), with the bit-planes and energy full coding
// reports; a slope just below that bound codes it. Both from a float plane and from indices.
TEST(T1StopRule, BlocksWorthNoPassAreNotCoded) {
  std::mt19937 rng(1207);
  std::normal_distribution<float> coefficient(0.0f, 3.0f);
  const int w = 32, h = 20, stride = 40;
  std::vector<float> plane(static_cast<std::size_t>(stride * h));
  for (float& c : plane) c = coefficient(rng);
  std::vector<std::int32_t> indices(plane.size());
  for (std::size_t i = 0; i < plane.size(); ++i) indices[i] = static_cast<std::int32_t>(plane[i] * 4.0f);
  const float inverse_step = 4.0f;
  const double weight = 0.25;
  for (const bool from_floats : {true, false}) {
    auto encode = [&](codec::t1::StopRule stop) {
      return from_floats ? codec::t1::encode_block(codec::t1::FloatBlock{plane.data(), stride, w, h, inverse_step},
                                                   Orientation::HH, 20, {}, stop)
                         : codec::t1::encode_block(codec::t1::IntegerBlock{indices.data(), stride, w, h},
                                                   Orientation::HH, 20, {}, stop);
    };
    const EncodedBlock full = encode({});
    ASSERT_GT(full.bit_planes, 2);
    ASSERT_FALSE(full.passes.empty());
    EXPECT_FALSE(full.stopped_early);
    const double bound = weight * full.energy;  // per byte
    const EncodedBlock skipped = encode(codec::t1::StopRule{bound * 1.001, weight});
    EXPECT_TRUE(skipped.passes.empty()) << "from floats: " << from_floats;
    EXPECT_TRUE(skipped.data.empty());
    EXPECT_TRUE(skipped.stopped_early);
    EXPECT_EQ(skipped.bit_planes, full.bit_planes);
    EXPECT_EQ(skipped.missing_msbs, full.missing_msbs);
    EXPECT_EQ(skipped.energy, full.energy);
    const EncodedBlock coded = encode(codec::t1::StopRule{bound * 0.999, weight});
    EXPECT_FALSE(coded.passes.empty()) << "from floats: " << from_floats;
    EXPECT_EQ(coded.energy, full.energy);
  }
}

// A pass limit ends the block after that many passes, as the last pass would: the passes kept
// measure what they did in the full coding, and the block says it stopped early (rate control's
// check for starved blocks depends on that); a limit at or past the last pass changes nothing.
TEST(T1StopRule, PassLimitEndsTheBlockThere) {
  std::mt19937 rng(77);
  std::normal_distribution<float> coefficient(0.0f, 40.0f);
  const int w = 24, h = 17;
  std::vector<float> plane(static_cast<std::size_t>(w * h));
  for (float& c : plane) c = coefficient(rng);
  auto encode = [&](codec::t1::StopRule stop) {
    return codec::t1::encode_block(codec::t1::FloatBlock{plane.data(), w, w, h, 1.0f}, Orientation::LH, 20, {}, stop);
  };
  const EncodedBlock full = encode({});
  const int count = static_cast<int>(full.passes.size());
  ASSERT_GT(count, 8);
  for (const int limit : {1, 4, 7, count - 1}) {
    const EncodedBlock limited = encode(codec::t1::StopRule{0, 1, limit});
    ASSERT_EQ(static_cast<int>(limited.passes.size()), limit);
    EXPECT_TRUE(limited.stopped_early);
    EXPECT_TRUE(limited.passes.back().terminated);
    for (int p = 0; p < limit; ++p)
      EXPECT_EQ(limited.passes[static_cast<std::size_t>(p)].distortion_decrease,
                full.passes[static_cast<std::size_t>(p)].distortion_decrease)
          << "limit " << limit << " pass " << p;
  }
  const EncodedBlock unlimited = encode(codec::t1::StopRule{0, 1, count});
  EXPECT_FALSE(unlimited.stopped_early);
  EXPECT_EQ(unlimited.data, full.data);
}

namespace {

// The stop rule's one-plane stop for a block no plane has paid for yet (block_encoder.cpp,
// stops_after_quiet_plane): a top plane that bought far less than the stop slope (under a 32nd of
// it) ends the block after that one pass; one only somewhat below it (a quarter) does not, and the
// block goes on to the next plane. The block: Gaussian coefficients with one outlier alone in the
// top bit-plane, so that the top plane's slope is poor while the block's energy keeps it well clear
// of the skip for blocks worth no pass.
TEST(T1StopRule, UnpaidBlockStopsAfterOnlyAFarQuietPlane) {
  std::mt19937 rng(2027);
  std::normal_distribution<float> coefficient(0.0f, 16.0f);
  const int w = 64, h = 64;
  std::vector<float> plane(static_cast<std::size_t>(w * h));
  for (float& c : plane) c = std::clamp(coefficient(rng), -63.0f, 63.0f);
  plane[static_cast<std::size_t>(37 * w + 21)] = 90.0f;  // alone in bit-plane 6
  auto encode = [&](codec::t1::StopRule stop) {
    return codec::t1::encode_block(codec::t1::FloatBlock{plane.data(), w, w, h, 1.0f}, Orientation::HH, 20, {}, stop);
  };
  const EncodedBlock full = encode({});
  ASSERT_EQ(full.bit_planes, 7);
  ASSERT_GT(full.passes.size(), 4u);
  // The top plane's slope with its shortest length, an upper bound of the coder's own estimate (its
  // byte count is at least that length).
  const double top_slope =
      full.passes[0].distortion_decrease / static_cast<double>(std::max<std::size_t>(full.passes[0].length, 1));
  const double far_below = 256 * top_slope, somewhat_below = 4 * top_slope;
  ASSERT_GT(full.energy, far_below) << "the block must not be skipped as worth no pass";

  const EncodedBlock stopped = encode(codec::t1::StopRule{far_below, 1});
  EXPECT_EQ(stopped.passes.size(), 1u);
  EXPECT_TRUE(stopped.stopped_early);
  EXPECT_EQ(stopped.passes[0].distortion_decrease, full.passes[0].distortion_decrease);

  const EncodedBlock going_on = encode(codec::t1::StopRule{somewhat_below, 1});
  EXPECT_GE(going_on.passes.size(), 4u);  // at least the next plane
}

}  // namespace
