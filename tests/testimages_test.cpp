// Tests for the synthetic test images: sizes, value ranges, determinism, and
// golden values that catch any change in the generated pixels (a PRNG or
// pattern change must be deliberate, since stored results depend on them).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "testimages/patterns.h"
#include "testimages/prng.h"

namespace {

using testimages::Pattern;

struct Size {
  int width;
  int height;
};

const std::vector<Size> kSizes = {{1, 1}, {1, 7}, {7, 1}, {3, 5}, {8, 8}, {127, 129}};

// FNV-1a over the sample values: a compact fingerprint of a whole image.
std::uint64_t fingerprint(const imageio::Image& image) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (float v : image.pixels) {
    const auto value = std::uint32_t(std::int32_t(v));
    for (int shift = 0; shift < 32; shift += 8) {
      hash = (hash ^ ((value >> shift) & 0xff)) * 0x100000001b3ULL;
    }
  }
  return hash;
}

bool channel_is_constant(const imageio::Image& image, int c) {
  const float first = image.at(0, 0, c);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y, c) != first) return false;
    }
  }
  return true;
}

TEST(Patterns, NamesRoundTrip) {
  for (Pattern pattern : testimages::kAllPatterns) {
    EXPECT_EQ(testimages::parse_pattern(testimages::pattern_name(pattern)), pattern);
  }
  EXPECT_EQ(testimages::parse_pattern("gradient-diag"), Pattern::GradientDiag);
  EXPECT_EQ(testimages::pattern_name(Pattern::ZonePlate), "zoneplate");
}

TEST(Patterns, UnknownNameListsTheValidOnes) {
  try {
    testimages::parse_pattern("checkerboard");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("checkerboard"), std::string::npos);
    for (Pattern pattern : testimages::kAllPatterns) {
      EXPECT_NE(message.find(testimages::pattern_name(pattern)), std::string::npos);
    }
  }
  EXPECT_THROW(testimages::parse_pattern(""), std::invalid_argument);
  EXPECT_THROW(testimages::parse_pattern("Noise"), std::invalid_argument);
}

TEST(Patterns, SizesAndMetadata) {
  for (Pattern pattern : testimages::kAllPatterns) {
    for (Size size : kSizes) {
      for (int channels : {1, 3, 4}) {
        const imageio::Image image = testimages::generate(pattern, size.width, size.height, channels, 10, true);
        EXPECT_EQ(image.width, size.width);
        EXPECT_EQ(image.height, size.height);
        EXPECT_EQ(image.channels, channels);
        EXPECT_EQ(image.bits_per_sample, 10);
        EXPECT_TRUE(image.is_signed);
        EXPECT_FALSE(image.is_float);
        EXPECT_EQ(image.pixels.size(), std::size_t(size.width) * std::size_t(size.height) * std::size_t(channels));
      }
    }
  }
}

TEST(Patterns, ValuesAreIntegersInRange) {
  for (int bits : {1, 8, 12, 16}) {
    for (bool is_signed : {false, true}) {
      const long lo = is_signed ? -(1L << (bits - 1)) : 0;
      const long hi = is_signed ? (1L << (bits - 1)) - 1 : (1L << bits) - 1;
      for (Pattern pattern : testimages::kAllPatterns) {
        for (Size size : kSizes) {
          SCOPED_TRACE(std::string(testimages::pattern_name(pattern)) + " " + std::to_string(size.width) + "x" +
                       std::to_string(size.height) + " bits " + std::to_string(bits) + (is_signed ? " signed" : ""));
          const imageio::Image image = testimages::generate(pattern, size.width, size.height, 3, bits, is_signed);
          for (float v : image.pixels) {
            ASSERT_EQ(v, float(long(v)));
            ASSERT_GE(v, float(lo));
            ASSERT_LE(v, float(hi));
          }
        }
      }
    }
  }
}

TEST(Patterns, FullRangeIsUsed) {
  // Every pattern spans the range of `bits`, so codecs see full-scale data.
  for (Pattern pattern : {Pattern::GradientH, Pattern::GradientV, Pattern::GradientDiag, Pattern::Edges, Pattern::Noise,
                          Pattern::ZonePlate}) {
    for (int bits : {1, 8, 12, 16}) {
      for (bool is_signed : {false, true}) {
        SCOPED_TRACE(std::string(testimages::pattern_name(pattern)) + " bits " + std::to_string(bits) +
                     (is_signed ? " signed" : ""));
        const imageio::Image image = testimages::generate(pattern, 127, 129, 1, bits, is_signed);
        const auto [min, max] = std::minmax_element(image.pixels.begin(), image.pixels.end());
        const float lo = is_signed ? -float(1L << (bits - 1)) : 0.0f;
        const float hi = float((1L << bits) - 1) + lo;
        if (pattern == Pattern::Noise || pattern == Pattern::ZonePlate) {
          // Sampled signals come close to both ends, but at 16 bits
          // 16k samples need not land exactly on them.
          const float slack = float(1L << bits) / 1000;
          EXPECT_LE(*min, lo + slack);
          EXPECT_GE(*max, hi - slack);
        } else {
          EXPECT_EQ(*min, lo);
          EXPECT_EQ(*max, hi);
        }
      }
    }
  }
}

TEST(Patterns, SignedIsUnsignedShiftedByHalfTheRange) {
  for (Pattern pattern : testimages::kAllPatterns) {
    const imageio::Image u = testimages::generate(pattern, 17, 9, 3, 12, false, 5);
    const imageio::Image s = testimages::generate(pattern, 17, 9, 3, 12, true, 5);
    for (std::size_t i = 0; i < u.pixels.size(); ++i) {
      ASSERT_EQ(s.pixels[i], u.pixels[i] - 2048.0f);
    }
  }
}

TEST(Patterns, EveryPatternAndChannelVaries) {
  for (Pattern pattern : testimages::kAllPatterns) {
    for (Size size : {Size{8, 8}, Size{9, 8}, Size{8, 13}, Size{127, 129}}) {
      for (int bits : {1, 8, 16}) {
        SCOPED_TRACE(std::string(testimages::pattern_name(pattern)) + " " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + " bits " + std::to_string(bits));
        const imageio::Image image = testimages::generate(pattern, size.width, size.height, 3, bits);
        for (int c = 0; c < 3; ++c) EXPECT_FALSE(channel_is_constant(image, c)) << c;
      }
    }
  }
}

TEST(Patterns, ChannelsDiffer) {
  for (Pattern pattern : testimages::kAllPatterns) {
    SCOPED_TRACE(testimages::pattern_name(pattern));
    const imageio::Image image = testimages::generate(pattern, 32, 32, 3, 8);
    for (int a = 0; a < 3; ++a) {
      for (int b = a + 1; b < 3; ++b) {
        bool differ = false;
        for (int y = 0; y < 32 && !differ; ++y) {
          for (int x = 0; x < 32 && !differ; ++x) {
            differ = image.at(x, y, a) != image.at(x, y, b);
          }
        }
        EXPECT_TRUE(differ) << "channels " << a << " and " << b;
      }
    }
  }
}

TEST(Patterns, Deterministic) {
  for (Pattern pattern : testimages::kAllPatterns) {
    const imageio::Image a = testimages::generate(pattern, 31, 17, 3, 12, false, 42);
    const imageio::Image b = testimages::generate(pattern, 31, 17, 3, 12, false, 42);
    EXPECT_EQ(a.pixels, b.pixels) << testimages::pattern_name(pattern);
  }
}

TEST(Patterns, SeedChangesNoiseOnly) {
  for (Pattern pattern : {Pattern::Noise, Pattern::Mix}) {
    const imageio::Image a = testimages::generate(pattern, 16, 16, 1, 8, false, 1);
    const imageio::Image b = testimages::generate(pattern, 16, 16, 1, 8, false, 2);
    EXPECT_NE(a.pixels, b.pixels) << testimages::pattern_name(pattern);
  }
  for (Pattern pattern :
       {Pattern::ZonePlate, Pattern::GradientH, Pattern::GradientV, Pattern::GradientDiag, Pattern::Edges}) {
    const imageio::Image a = testimages::generate(pattern, 16, 16, 1, 8, false, 1);
    const imageio::Image b = testimages::generate(pattern, 16, 16, 1, 8, false, 2);
    EXPECT_EQ(a.pixels, b.pixels) << testimages::pattern_name(pattern);
  }
}

TEST(Patterns, ZonePlateCentreIsBright) {
  // cos(0) = 1 at the centre of an odd-sized image.
  const imageio::Image image = testimages::generate(Pattern::ZonePlate, 9, 11, 1, 8);
  EXPECT_EQ(image.at(4, 5, 0), 255.0f);
}

TEST(Patterns, InvalidArgumentsAreRejected) {
  EXPECT_THROW(testimages::generate(Pattern::Noise, 0, 5, 1, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 5, 0, 1, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, -3, 5, 1, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 65536, 1, 1, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 1, 65536, 1, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 5, 5, 0, 8), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 5, 5, 1, 0), std::invalid_argument);
  EXPECT_THROW(testimages::generate(Pattern::Noise, 5, 5, 1, 17), std::invalid_argument);
  EXPECT_NO_THROW(testimages::generate(Pattern::Mix, 65535, 1, 1, 8));
  EXPECT_NO_THROW(testimages::generate(Pattern::Mix, 1, 65535, 1, 8));
}

// ------------------------------------------------------------ golden values

TEST(Prng, MatchesPublishedSplitMix64) {
  // The first outputs of SplitMix64 seeded with 0, as published with the
  // reference implementation.
  const std::uint64_t expected[] = {0xE220A8397B1DCDAFULL, 0x6E789E6AA1B965F4ULL, 0x06C45D188009454FULL,
                                    0xF88BB8A8724C81ECULL};
  testimages::SplitMix64 rng(0);
  for (std::uint64_t i = 0; i < 4; ++i) {
    EXPECT_EQ(rng.next(), expected[i]);
    EXPECT_EQ(testimages::splitmix64_at(0, i), expected[i]);
  }
}

TEST(Golden, NoiseSamples) {
  // Noise takes the top `bits` bits of one SplitMix64 output per sample.
  const imageio::Image image = testimages::generate(Pattern::Noise, 3, 2, 1, 16, false, 1);
  const std::vector<float> expected = {37130, 48875, 63635, 29121, 29115, 49997};
  EXPECT_EQ(image.pixels, expected);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    EXPECT_EQ(image.pixels[i], float(testimages::splitmix64_at(1, i) >> 48));
  }
}

TEST(Golden, Fingerprints) {
  // If a pattern is changed on purpose, update these values; if they change
  // on another platform or compiler, the generator is not portable.
  struct Case {
    Pattern pattern;
    std::uint64_t fingerprint;
  };
  const Case cases[] = {
      {Pattern::ZonePlate, 0xD8B2DDE27C1A439BULL}, {Pattern::GradientH, 0xC5F4D97467CFD922ULL},
      {Pattern::GradientV, 0xF48B7AF1F3FF248DULL}, {Pattern::GradientDiag, 0x72D6CAF31CB2AA6BULL},
      {Pattern::Edges, 0x328273F77F5E347DULL},     {Pattern::Noise, 0x1534AB404E8D837EULL},
      {Pattern::Mix, 0xA2A9D3B9F4468F1EULL},
  };
  for (const Case& c : cases) {
    const imageio::Image image = testimages::generate(c.pattern, 37, 23, 3, 12, false, 7);
    EXPECT_EQ(fingerprint(image), c.fingerprint) << testimages::pattern_name(c.pattern);
  }
}

}  // namespace
