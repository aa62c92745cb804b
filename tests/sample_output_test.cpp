// The decoder's last stage (codec/decoder/src/sample_output.h): the vectorised rows that turn the
// inverse DWT's planes into output samples (inverse RCT / ICT, level shift, rounding, clamping)
// against the scalar reference rows, sample for sample, on rows of every length from 0 to 70 (so
// that each vector width leaves every possible remainder), every kind of range, values far outside
// the range, halves (ties to even), NaN and infinities; and the reference against hand-worked values.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "sample_output.h"

namespace {

using codec::dec::OutputRanges;
using codec::dec::OutputRows;
using codec::dec::sample_range;
using codec::dec::SampleRange;

// Ranges of 8-bit to 31-bit, signed and unsigned components, with those too wide for float lanes.
std::vector<SampleRange> ranges() {
  std::vector<SampleRange> out;
  for (int precision : {1, 5, 8, 12, 16, 24, 25, 26, 31})
    for (bool is_signed : {false, true}) out.push_back(sample_range(precision, is_signed));
  return out;
}

std::vector<float> random_floats(std::mt19937& rng, std::size_t n, float scale) {
  std::uniform_real_distribution<float> value(-scale, scale);
  std::uniform_int_distribution<int> kind(0, 15);
  std::vector<float> v(n);
  for (float& f : v) {
    switch (kind(rng)) {
      case 0:
        f = std::numeric_limits<float>::quiet_NaN();
        break;
      case 1:
        f = kind(rng) < 8 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
        break;
      case 2:
        f = std::floor(value(rng)) + 0.5f;
        break;  // a tie
      case 3:
        f = std::nextafter(0.5f, 0.0f) + std::floor(value(rng));
        break;
      case 4:
        f = value(rng) * 1e9f;
        break;
      default:
        f = value(rng);
    }
  }
  return v;
}

std::vector<std::int32_t> random_ints(std::mt19937& rng, std::size_t n, std::int32_t scale) {
  std::uniform_int_distribution<std::int32_t> value(-scale, scale);
  std::uniform_int_distribution<std::int32_t> any(std::numeric_limits<std::int32_t>::min(),
                                                  std::numeric_limits<std::int32_t>::max());
  std::uniform_int_distribution<int> kind(0, 9);
  std::vector<std::int32_t> v(n);
  for (std::int32_t& i : v) i = kind(rng) == 0 ? any(rng) : value(rng);
  return v;
}

TEST(SampleOutput, RangesFollowTheComponentPrecision) {
  const SampleRange u8 = sample_range(8, false), s12 = sample_range(12, true), u31 = sample_range(31, false);
  EXPECT_EQ(u8.shift, 128);
  EXPECT_EQ(u8.lo, 0);
  EXPECT_EQ(u8.hi, 255);
  EXPECT_EQ(s12.shift, 0);
  EXPECT_EQ(s12.lo, -2048);
  EXPECT_EQ(s12.hi, 2047);
  EXPECT_EQ(u31.shift, 1 << 30);
  EXPECT_EQ(u31.hi, std::numeric_limits<std::int32_t>::max());
}

TEST(SampleOutput, ReferenceRowsMatchHandWorkedValues) {
  const SampleRange u8 = sample_range(8, false);
  const float floats[] = {2.5f,
                          3.5f,
                          -0.5f,
                          -128.7f,
                          200.0f,
                          std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity()};
  std::int32_t out[7];
  codec::dec::reference::floats_to_samples(floats, u8, out, 7);
  const std::int32_t expected[] = {130, 132, 128, 0, 255, 128, 128};  // ties to even, clamped, not finite: 0
  for (int i = 0; i < 7; ++i) EXPECT_EQ(out[i], expected[i]) << i;

  // G-7 on Y = 10, Cb = -3, Cr = 6: G = 10 - floor(3 / 4) = 10, R = 16, B = 7.
  const std::int32_t y = 10, cb = -3, cr = 6;
  std::int32_t r = 0, g = 0, b = 0;
  codec::dec::reference::rct_to_samples(&y, &cb, &cr, {u8, u8, u8}, {&r, &g, &b}, 1);
  EXPECT_EQ(r, 16 + 128);
  EXPECT_EQ(g, 10 + 128);
  EXPECT_EQ(b, 7 + 128);
}

TEST(SampleOutput, PlaneRowsEqualTheReference) {
  std::mt19937 rng(17);
  for (const SampleRange& range : ranges())
    for (std::size_t n = 0; n <= 70; ++n) {
      const float scale = static_cast<float>(range.hi - range.lo) * 0.75f + 4.0f;
      const std::vector<float> floats = random_floats(rng, n, scale);
      const std::vector<std::int32_t> ints = random_ints(rng, n, static_cast<std::int32_t>(std::min(scale, 2e9f)));
      std::vector<std::int32_t> got(n + 1, -7), want(n + 1, -7);  // one guard sample past the row
      codec::dec::floats_to_samples(floats.data(), range, got.data(), n);
      codec::dec::reference::floats_to_samples(floats.data(), range, want.data(), n);
      ASSERT_EQ(got, want) << "floats, n " << n << ", range " << range.lo << ".." << range.hi;
      codec::dec::ints_to_samples(ints.data(), range, got.data(), n);
      codec::dec::reference::ints_to_samples(ints.data(), range, want.data(), n);
      ASSERT_EQ(got, want) << "ints, n " << n << ", range " << range.lo << ".." << range.hi;
    }
}

TEST(SampleOutput, TransformRowsEqualTheReference) {
  std::mt19937 rng(18);
  const std::vector<SampleRange> all = ranges();
  for (std::size_t k = 0; k < all.size(); ++k)
    for (std::size_t n = 0; n <= 70; ++n) {
      // Components of different ranges, and now and then one that is not output.
      const OutputRanges r = {all[k], all[(k + 3) % all.size()], all[(k + 7) % all.size()]};
      const std::size_t skipped = n % 5;  // 3 or 4: all three output
      const float scale = static_cast<float>(r[0].hi - r[0].lo) * 0.75f + 4.0f;
      std::array<std::vector<float>, 3> f;
      std::array<std::vector<std::int32_t>, 3> i;
      for (std::size_t c = 0; c < 3; ++c) {
        f[c] = random_floats(rng, n, scale);
        i[c] = random_ints(rng, n, static_cast<std::int32_t>(std::min(scale, 2e9f)));
      }
      std::array<std::vector<std::int32_t>, 3> got, want;
      OutputRows got_rows{}, want_rows{};
      for (std::size_t c = 0; c < 3; ++c) {
        got[c].assign(n + 1, -7);
        want[c].assign(n + 1, -7);
        if (c != skipped) {
          got_rows[c] = got[c].data();
          want_rows[c] = want[c].data();
        }
      }
      codec::dec::ict_to_samples(f[0].data(), f[1].data(), f[2].data(), r, got_rows, n);
      codec::dec::reference::ict_to_samples(f[0].data(), f[1].data(), f[2].data(), r, want_rows, n);
      ASSERT_EQ(got, want) << "ICT, n " << n << ", range " << k;
      codec::dec::rct_to_samples(i[0].data(), i[1].data(), i[2].data(), r, got_rows, n);
      codec::dec::reference::rct_to_samples(i[0].data(), i[1].data(), i[2].data(), r, want_rows, n);
      ASSERT_EQ(got, want) << "RCT, n " << n << ", range " << k;
    }
}

}  // namespace
