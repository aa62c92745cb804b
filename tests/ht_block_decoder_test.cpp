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
#include <span>
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

// A set of only a cleanup segment on `plane`.
codec::ht::HtCodewords cleanup_only(std::span<const std::uint8_t> cleanup, int plane) {
  codec::ht::HtCodewords set;
  set.cleanup = cleanup;
  set.cleanup_plane = plane;
  return set;
}

std::int32_t expected_sample(std::int32_t q, int plane) {
  const std::uint32_t magnitude =
      q < 0 ? static_cast<std::uint32_t>(-static_cast<std::int64_t>(q)) : static_cast<std::uint32_t>(q);
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
    codec::ht::decode_ht_block(cleanup_only({}, plane), width, height, out);
  } else {
    EXPECT_EQ(coded.missing_msbs, mb - 1 - plane);
    codec::ht::decode_ht_block(cleanup_only(coded.data, mb - 1 - coded.missing_msbs), width, height, out);
  }
  for (std::size_t i = 0; i < q.size(); ++i)
    if (out[i] != expected_sample(q[i], plane))
      return std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(planes) +
             " planes, cleanup plane " + std::to_string(plane) + ": sample " + std::to_string(i) + " reads " +
             std::to_string(out[i]) + ", expected " + std::to_string(expected_sample(q[i], plane));
  return {};
}

TEST(HtBlockDecoder, EveryShapeAndPlaneCountRoundTrips) {
  std::mt19937 rng(20261217);
  const int shapes[][2] = {{4, 1024}, {1024, 4}, {64, 64}, {32, 32}, {1, 1},  {1, 7},  {7, 1},
                           {3, 5},    {17, 9},   {63, 65}, {2, 2},   {5, 64}, {64, 5}, {33, 31}};
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
  codec::ht::decode_ht_block(cleanup_only({}, 0), 64, 64, out);
  for (std::int32_t v : out) ASSERT_EQ(v, 0);
}

TEST(HtBlockDecoder, MalformedSegmentsAreRefusedWithoutReadingOutside) {
  std::vector<std::int32_t> out(16 * 16);
  // Scup larger than the segment.
  const std::vector<std::uint8_t> too_long{0x00, 0x0F, 0xFF};
  EXPECT_THROW(codec::ht::decode_ht_block(cleanup_only(too_long, 0), 16, 16, out), codec::ht::HtDecodeError);
  const std::vector<std::uint8_t> one_byte{0x00};
  EXPECT_THROW(codec::ht::decode_ht_block(cleanup_only(one_byte, 0), 16, 16, out), codec::ht::HtDecodeError);
  // Random segments with a valid Scup decode to something or are refused, never crash (ASan).
  std::mt19937 rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> d(2 + rng() % 60);
    for (auto& b : d) b = static_cast<std::uint8_t>(rng());
    const std::size_t scup = 2 + rng() % (d.size() - 1);
    d[d.size() - 1] = static_cast<std::uint8_t>(scup >> 4);
    d[d.size() - 2] = static_cast<std::uint8_t>((d[d.size() - 2] & 0xF0) | (scup & 0x0F));
    try {
      codec::ht::decode_ht_block(cleanup_only(d, static_cast<int>(rng() % 20)), 16, 16, out);
    } catch (const codec::ht::HtDecodeError&) {
    }
  }
}

// ---- SigProp and MagRef against a model of their encoding ---------------------------------------
// No encoder at hand writes refinement passes (ours, ojph_compress and grk_compress code the cleanup
// pass only), so the test writes them itself from T.814 7.4 and 7.5, stated differently from the
// decoder: a neighbour counts with what SigProp found when it was visited earlier (stripe, then
// column, then row), else with the cleanup's significance.

// Forward bit-packing of SigProp (7 bits after 0xFF) and backward packing of MagRef (VLC stuffing).
struct RefinementBits {
  std::vector<std::uint8_t> forward;
  std::uint32_t forward_byte = 0, forward_last = 0;
  int forward_used = 0;
  std::vector<std::uint8_t> backward;  // in the order written: the segment's last byte first
  std::uint32_t backward_byte = 0, backward_last = 0xFF;
  int backward_used = 0;

  void sig_prop(int bit) {
    forward_byte |= static_cast<std::uint32_t>(bit) << forward_used;
    if (++forward_used == (forward_last == 0xFF ? 7 : 8)) {
      forward.push_back(static_cast<std::uint8_t>(forward_byte));
      forward_last = forward_byte;
      forward_byte = 0;
      forward_used = 0;
    }
  }
  void mag_ref(int bit) {
    backward_byte |= static_cast<std::uint32_t>(bit) << backward_used;
    ++backward_used;
    if (backward_last > 0x8F && backward_byte == 0x7F) ++backward_used;  // bit 7 stuffed
    if (backward_used == 8) {
      backward.push_back(static_cast<std::uint8_t>(backward_byte));
      backward_last = backward_byte;
      backward_byte = 0;
      backward_used = 0;
    }
  }
  std::vector<std::uint8_t> segment() {
    if (forward_used > 0) forward.push_back(static_cast<std::uint8_t>(forward_byte));
    if (backward_used > 0) backward.push_back(static_cast<std::uint8_t>(backward_byte));
    std::vector<std::uint8_t> d = forward;
    d.insert(d.end(), backward.rbegin(), backward.rend());
    return d;
  }
};

struct ModelRefinement {
  std::vector<std::uint8_t> segment;
  std::vector<std::int32_t> expected_one_pass, expected_two_passes;
};

ModelRefinement model_refinement(const std::vector<std::int32_t>& q, int w, int h, int p, bool causal) {
  const auto n = q.size();
  auto magnitude = [&](std::size_t i) {
    return static_cast<std::uint32_t>(q[i] < 0 ? -static_cast<std::int64_t>(q[i]) : q[i]);
  };
  auto at = [&](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
  };
  std::vector<int> cleanup(n), found(n, 0);
  for (std::size_t i = 0; i < n; ++i) cleanup[i] = (magnitude(i) >> p) != 0;
  auto visited_before = [&](int nx, int ny, int x, int y) {
    if (ny / 4 != y / 4) return ny / 4 < y / 4;
    return nx < x || (nx == x && ny < y);
  };
  RefinementBits bits;
  for (int y0 = 0; y0 < h; y0 += 4)
    for (int x0 = 0; x0 < w; x0 += 4) {
      std::vector<std::size_t> group_found;
      for (int x = x0; x < std::min(x0 + 4, w); ++x)
        for (int y = y0; y < std::min(y0 + 4, h); ++y) {
          if (cleanup[at(x, y)]) continue;
          bool neighbour = false;
          for (int ny = y - 1; ny <= y + 1; ++ny)
            for (int nx = x - 1; nx <= x + 1; ++nx) {
              if ((nx == x && ny == y) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
              if (causal && ny / 4 > y / 4) continue;
              neighbour |= cleanup[at(nx, ny)] || (visited_before(nx, ny, x, y) && found[at(nx, ny)]);
            }
          if (!neighbour) continue;
          const int bit = static_cast<int>((magnitude(at(x, y)) >> (p - 1)) & 1);
          bits.sig_prop(bit);
          if (bit) {
            found[at(x, y)] = 1;
            group_found.push_back(at(x, y));
          }
        }
      for (std::size_t i : group_found) bits.sig_prop(q[i] < 0 ? 1 : 0);
    }
  for (int y0 = 0; y0 < h; y0 += 4)
    for (int x = 0; x < w; ++x)
      for (int y = y0; y < std::min(y0 + 4, h); ++y)
        if (cleanup[at(x, y)]) bits.mag_ref(static_cast<int>((magnitude(at(x, y)) >> (p - 1)) & 1));
  ModelRefinement m;
  m.segment = bits.segment();
  m.expected_one_pass.assign(n, 0);
  m.expected_two_passes.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t sign = q[i] < 0 ? -1 : 1;
    if (cleanup[i]) {
      m.expected_one_pass[i] = expected_sample(q[i], p);
      m.expected_two_passes[i] = expected_sample(q[i], p - 1);
    } else if (found[i]) {
      m.expected_one_pass[i] = m.expected_two_passes[i] = sign * (3 << (p - 1));
    }
  }
  return m;
}

TEST(HtBlockDecoder, SigPropAndMagRefAgainstTheModel) {
  std::mt19937 rng(1517);
  const int shapes[][2] = {{64, 64}, {32, 32}, {4, 1024}, {1024, 4}, {17, 9}, {5, 3}, {1, 1}, {13, 64}};
  int checked = 0;
  for (const auto& s : shapes)
    for (int planes : {2, 5, 12})
      for (double density : {0.05, 0.3, 0.9})
        for (bool causal : {false, true}) {
          const auto q = random_block(rng, s[0], s[1], planes, density);
          const int p = 1 + static_cast<int>(rng() % static_cast<unsigned>(planes - 1));
          const codec::t1::EncodedBlock coded = codec::ht::encode_ht_block(q, s[0], s[1], planes, p);
          if (coded.passes.empty()) continue;
          const ModelRefinement m = model_refinement(q, s[0], s[1], p, causal);
          for (int passes : {1, 2}) {
            codec::ht::HtCodewords set = cleanup_only(coded.data, p);
            set.refinement = m.segment;
            set.refinement_passes = passes;
            set.vertically_causal = causal;
            std::vector<std::int32_t> out(q.size());
            codec::ht::decode_ht_block(set, s[0], s[1], out);
            const auto& want = passes == 1 ? m.expected_one_pass : m.expected_two_passes;
            for (std::size_t i = 0; i < q.size(); ++i)
              ASSERT_EQ(out[i], want[i]) << s[0] << "x" << s[1] << ", " << planes << " planes, cleanup plane " << p
                                         << ", " << passes << " refinement pass(es)" << (causal ? ", causal" : "")
                                         << ": sample " << i;
            ++checked;
          }
        }
  EXPECT_GT(checked, 200);
}

TEST(HtBlockDecoder, RefinementBelowPlaneZeroIsRefused) {
  std::mt19937 rng(5);
  const auto q = random_block(rng, 8, 8, 4, 0.5);
  const codec::t1::EncodedBlock coded = codec::ht::encode_ht_block(q, 8, 8, 4, 0);
  codec::ht::HtCodewords set = cleanup_only(coded.data, 0);
  const std::vector<std::uint8_t> refinement{0x12, 0x34};
  set.refinement = refinement;
  set.refinement_passes = 2;
  std::vector<std::int32_t> out(q.size());
  EXPECT_THROW(codec::ht::decode_ht_block(set, 8, 8, out), codec::ht::HtDecodeError);
}

}  // namespace
