// The decoder's tier-1 (codec/decoder/src/block_decoder.cpp, stripe-column words and lookup
// tables) against the straightforward decoder it replaced (t1_decoder_reference.h): random blocks
// coded by our encoder in every orientation, every combination of the six code-block style
// switches, shapes from 1x1 to 64x64 and 1024x4, many bit-plane counts, then decoded whole, with
// passes left out, with segments cut short and with the data cut short; and random bytes in place
// of a codeword. The two decoders' outputs must be identical, sample for sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "block_decoder.h"
#include "codec/t1/block_encoder.h"
#include "codec/t1/block_style.h"
#include "codec/tier2/codeword_segments.h"
#include "t1_decoder_reference.h"

namespace {

using codec::BandOrientation;
using codec::dec::BlockCodewords;
using codec::dec::Segment;
using codec::t1::BlockStyle;
using codec::t1::Orientation;

BandOrientation band_of(Orientation o) {
  switch (o) {
    case Orientation::HL:
      return BandOrientation::HL;
    case Orientation::LH:
      return BandOrientation::LH;
    case Orientation::HH:
      return BandOrientation::HH;
    default:
      return BandOrientation::LL;
  }
}

// Coefficients with magnitudes below 2^planes: sparse, dense or Laplacian-like, with signs.
std::vector<std::int32_t> random_coefficients(int w, int h, int planes, std::mt19937& rng) {
  std::vector<std::int32_t> c(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
  const std::uint32_t limit = planes >= 31 ? 0x7FFFFFFFu : (1u << planes) - 1;
  std::uniform_int_distribution<std::uint32_t> magnitude(0, limit);
  std::uniform_int_distribution<int> percent(0, 99);
  std::exponential_distribution<double> laplace(1.0 / std::max(1.0, static_cast<double>(limit) / 16));
  for (auto& v : c) {
    std::uint32_t m = 0;
    if (kind == 0)
      m = percent(rng) < 5 ? magnitude(rng) : 0;
    else if (kind == 1)
      m = magnitude(rng);
    else
      m = static_cast<std::uint32_t>(std::min<double>(laplace(rng), limit));
    v = percent(rng) < 50 ? -static_cast<std::int32_t>(m) : static_cast<std::int32_t>(m);
  }
  c[0] = static_cast<std::int32_t>(limit);  // every plane in use
  return c;
}

// The segments a packet header would announce for the first `passes` passes of `enc`.
std::vector<Segment> segments_of(const codec::t1::EncodedBlock& enc, const BlockStyle& style, int passes) {
  std::vector<Segment> segments;
  const auto pieces = codec::t2::split_into_segments(
      style, 0, passes, [&](int pass) { return enc.passes[static_cast<std::size_t>(pass)].length; });
  for (const auto& p : pieces) segments.push_back(Segment{p.bytes, p.passes});
  return segments;
}

void expect_same(const BlockCodewords& block, int w, int h, Orientation o, const BlockStyle& style,
                 const std::string& what) {
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<std::int32_t> fast(n, 7), reference(n, 7);
  codec::dec::decode_code_block(block, w, h, band_of(o), style, fast);
  t1dec_ref::decode_code_block(block, w, h, band_of(o), style, reference);
  const auto differ = std::mismatch(fast.begin(), fast.end(), reference.begin());
  ASSERT_TRUE(differ.first == fast.end()) << what << ": sample " << (differ.first - fast.begin()) << " decodes to "
                                          << *differ.first << ", the reference says " << *differ.second;
}

std::string describe(int w, int h, Orientation o, const BlockStyle& s, int planes, const char* variant) {
  std::ostringstream os;
  os << w << "x" << h << " orientation " << static_cast<int>(o) << " style 0x" << std::hex
     << static_cast<int>(s.to_spcod()) << std::dec << " planes " << planes << " " << variant;
  return os.str();
}

TEST(T1Decoder, MatchesReferenceOnEncodedBlocks) {
  std::mt19937 rng(20240517);
  const std::pair<int, int> shapes[] = {{4, 4}, {64, 64}, {32, 32}, {16, 64}, {64, 16}, {1024, 4}, {8, 8},
                                        {1, 1}, {5, 7},   {13, 6},  {3, 33},  {64, 1},  {2, 128}};
  std::uniform_int_distribution<int> plane_count(1, 31);
  int checked = 0;
  for (int spcod = 0; spcod < 64; ++spcod) {
    const BlockStyle style = BlockStyle::from_spcod(static_cast<std::uint8_t>(spcod));
    for (int oi = 0; oi < 4; ++oi) {
      const auto o = static_cast<Orientation>(oi);
      for (int rep = 0; rep < 2; ++rep) {
        const auto [w, h] = shapes[std::uniform_int_distribution<std::size_t>(0, std::size(shapes) - 1)(rng)];
        // Mostly the bit-plane counts images have, sometimes up to the most the decoder takes.
        const int planes = rep == 0 ? std::uniform_int_distribution<int>(1, 12)(rng) : plane_count(rng);
        if (planes > codec::dec::kMaxTopPlane + 1) continue;
        const auto coefficients = random_coefficients(w, h, planes, rng);
        const auto enc = codec::t1::encode_block(coefficients, w, h, o, planes, style);
        const int total = static_cast<int>(enc.passes.size());
        ASSERT_EQ(total, 3 * planes - 2);

        // Everything.
        auto segments = segments_of(enc, style, total);
        BlockCodewords block{enc.data, segments, total, planes - 1};
        expect_same(block, w, h, o, style, describe(w, h, o, style, planes, "whole"));

        // The first k passes only (a layer boundary), their segments as announced.
        const int k = std::uniform_int_distribution<int>(1, total)(rng);
        segments = segments_of(enc, style, k);
        const std::size_t bytes = enc.passes[static_cast<std::size_t>(k - 1)].length;
        block = BlockCodewords{std::span(enc.data).first(bytes), segments, k, planes - 1};
        expect_same(block, w, h, o, style, describe(w, h, o, style, planes, "passes cut"));

        // The last segment cut short (a truncated stream): fewer bytes than announced.
        if (bytes > 0) {
          const std::size_t keep = std::uniform_int_distribution<std::size_t>(0, bytes - 1)(rng);
          block.data = std::span(enc.data).first(keep);
          expect_same(block, w, h, o, style, describe(w, h, o, style, planes, "bytes cut"));
        }

        // More passes announced than the planes hold (a malformed header): both stop early.
        segments = segments_of(enc, style, total);
        block = BlockCodewords{enc.data, segments, total, std::max(0, planes - 3)};
        expect_same(block, w, h, o, style, describe(w, h, o, style, planes, "top plane too low"));
        checked += 4;
      }
    }
  }
  EXPECT_GT(checked, 1500);
}

// Random bytes as codewords (with 0xFF bytes and marker-like pairs on purpose), random segment
// splits and pass counts: the decoders must agree on garbage too, byte-in and raw-bit edge cases
// included.
TEST(T1Decoder, MatchesReferenceOnRandomBytes) {
  std::mt19937 rng(7);
  for (int i = 0; i < 1500; ++i) {
    const BlockStyle style = BlockStyle::from_spcod(static_cast<std::uint8_t>(i % 64));
    const auto o = static_cast<Orientation>((i / 64) % 4);
    const int w = std::uniform_int_distribution<int>(1, 64)(rng);
    const int h = std::uniform_int_distribution<int>(1, 4096 / w)(rng);
    std::vector<std::uint8_t> data(std::uniform_int_distribution<std::size_t>(0, 600)(rng));
    const int ff_percent = std::uniform_int_distribution<int>(0, 30)(rng);
    for (auto& b : data)
      b = std::uniform_int_distribution<int>(0, 99)(rng) < ff_percent
              ? 0xFF
              : static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(rng));
    const int top_plane = std::uniform_int_distribution<int>(0, codec::dec::kMaxTopPlane)(rng);
    const int passes = std::uniform_int_distribution<int>(1, 3 * top_plane + 1)(rng);
    std::vector<Segment> segments;
    std::size_t left = data.size();
    for (int p = 0; p < passes;) {
      const int n = std::uniform_int_distribution<int>(1, passes - p)(rng);
      const std::size_t b = std::uniform_int_distribution<std::size_t>(0, left)(rng);
      segments.push_back(Segment{b, n});
      left -= b;
      p += n;
    }
    const BlockCodewords block{data, segments, passes, top_plane};
    expect_same(block, w, h, o, style, describe(w, h, o, style, top_plane + 1, "random bytes"));
  }
}

}  // namespace
