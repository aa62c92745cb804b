// The HT cleanup decoder (codec/ht ht_block_decoder) against the HT encoder: random blocks of every
// code-block shape (4x1024, 1024x4, 64x64, 32x32, odd edge sizes) and every bit-plane count, coded
// from every cleanup plane, must decode to exactly what the encoder kept: sign * (2 (|q| >> p) + 1)
// << p, the EBCOT decoder's representation. The encoder itself is checked against an independent
// model of the standard in ht_block_test and against OpenJPEG, Grok and OpenJPH in j2k_ht_test; the
// decoder against OpenJPH's streams in j2k_ht_decode_test.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "codec/ht/ht_block_decoder.h"
#include "codec/ht/ht_block_encoder.h"

namespace {

// A random block whose magnitudes use up to `planes` bits; `density` of the samples are non-zero,
// with bit lengths spread over 1..planes so that quads mix small and large exponents.
std::vector<std::int32_t> random_block(std::mt19937& rng, int width, int height, int planes, double density) {
  std::vector<std::int32_t> q(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  std::bernoulli_distribution nonzero(density), negative(0.5);
  std::uniform_int_distribution<int> length(1, planes);
  for (std::int32_t& v : q) {
    if (!nonzero(rng)) continue;
    const int bits = length(rng);
    const std::uint32_t top = std::uint32_t{1} << (bits - 1);
    const std::uint32_t magnitude = top | (static_cast<std::uint32_t>(rng()) & (top - 1));
    v = negative(rng) ? -static_cast<std::int32_t>(magnitude) : static_cast<std::int32_t>(magnitude);
  }
  // The top plane must be used, so that the block has exactly `planes` bit-planes.
  q[static_cast<std::size_t>(rng() % q.size())] = static_cast<std::int32_t>(std::uint32_t{1} << (planes - 1));
  return q;
}

std::int32_t expected_sample(std::int32_t q, int plane) {
  const std::uint32_t magnitude = q < 0 ? static_cast<std::uint32_t>(-static_cast<std::int64_t>(q)) : static_cast<std::uint32_t>(q);
  const std::uint32_t mu = magnitude >> plane;
  if (mu == 0) return 0;
  const auto v = static_cast<std::int32_t>((2 * mu + 1) << plane);
  return q < 0 ? -v : v;
}

// Codes `q` from `plane` and decodes it back; returns the first mismatch as a message.
std::string round_trip(const std::vector<std::int32_t>& q, int width, int height, int planes, int plane) {
  const int mb = planes;  // Mb: the block uses every magnitude plane
  const codec::t1::EncodedBlock coded = codec::ht::encode_ht_block(q, width, height, mb, plane);
  std::vector<std::int32_t> out(q.size(), 7);
  if (coded.passes.empty()) {
    // Nothing at or above the plane: no cleanup segment; the decoder leaves zeros.
    codec::ht::decode_ht_block(codec::ht::HtCodewords{{}, plane}, width, height, out);
  } else {
    EXPECT_EQ(coded.missing_msbs, mb - 1 - plane);
    codec::ht::decode_ht_block(codec::ht::HtCodewords{coded.data, mb - 1 - coded.missing_msbs}, width, height, out);
  }
  for (std::size_t i = 0; i < q.size(); ++i)
    if (out[i] != expected_sample(q[i], plane))
      return std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(planes) + " planes, cleanup plane " +
             std::to_string(plane) + ": sample " + std::to_string(i) + " reads " + std::to_string(out[i]) + ", expected " +
             std::to_string(expected_sample(q[i], plane));
  return {};
}

TEST(HtBlockDecoder, EveryShapeAndPlaneCountRoundTrips) {
  std::mt19937 rng(20261217);
  const int shapes[][2] = {{4, 1024}, {1024, 4}, {64, 64}, {32, 32}, {1, 1}, {1, 7}, {7, 1}, {3, 5},
                           {17, 9}, {63, 65}, {2, 2}, {5, 64}, {64, 5}, {33, 31}};
  for (const auto& s : shapes)
    for (int planes = 1; planes <= 29; ++planes) {
      for (double density : {0.03, 0.4, 1.0}) {
        const auto q = random_block(rng, s[0], s[1], planes, density);
        // Lossless, the top plane, and one plane in between.
        for (int plane : {0, planes - 1, planes / 2}) {
          const std::string error = round_trip(q, s[0], s[1], planes, plane);
          ASSERT_TRUE(error.empty()) << error;
        }
      }
    }
}

TEST(HtBlockDecoder, EveryCleanupPlaneOfA64x64Block) {
  std::mt19937 rng(7);
  for (int planes : {8, 16, 24}) {
    const auto q = random_block(rng, 64, 64, planes, 0.5);
    for (int plane = 0; plane < planes; ++plane) {
      const std::string error = round_trip(q, 64, 64, planes, plane);
      ASSERT_TRUE(error.empty()) << error;
    }
  }
}

TEST(HtBlockDecoder, AllZeroBlockAtAPlaneHasNoSegment) {
  const std::vector<std::int32_t> q(64 * 64, 0);
  const codec::t1::EncodedBlock coded = codec::ht::encode_ht_block(q, 64, 64, 10, 0);
  EXPECT_TRUE(coded.passes.empty());
  std::vector<std::int32_t> out(q.size(), 5);
  codec::ht::decode_ht_block(codec::ht::HtCodewords{{}, 0}, 64, 64, out);
  for (std::int32_t v : out) ASSERT_EQ(v, 0);
}

TEST(HtBlockDecoder, MalformedSegmentsAreRefusedWithoutReadingOutside) {
  std::vector<std::int32_t> out(16 * 16);
  // Scup larger than the segment.
  const std::vector<std::uint8_t> too_long{0x00, 0x0F, 0xFF};
  EXPECT_THROW(codec::ht::decode_ht_block(codec::ht::HtCodewords{too_long, 0}, 16, 16, out), codec::ht::HtDecodeError);
  const std::vector<std::uint8_t> one_byte{0x00};
  EXPECT_THROW(codec::ht::decode_ht_block(codec::ht::HtCodewords{one_byte, 0}, 16, 16, out), codec::ht::HtDecodeError);
  // Random segments with a valid Scup decode to something or are refused, never crash (ASan).
  std::mt19937 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> d(2 + rng() % 60);
    for (auto& b : d) b = static_cast<std::uint8_t>(rng());
    const std::size_t scup = 2 + rng() % (d.size() - 1);
    d[d.size() - 1] = static_cast<std::uint8_t>(scup >> 4);
    d[d.size() - 2] = static_cast<std::uint8_t>((d[d.size() - 2] & 0xF0) | (scup & 0x0F));
    try {
      codec::ht::decode_ht_block(codec::ht::HtCodewords{d, static_cast<int>(rng() % 20)}, 16, 16, out);
    } catch (const codec::ht::HtDecodeError&) {
    }
  }
}

}  // namespace
