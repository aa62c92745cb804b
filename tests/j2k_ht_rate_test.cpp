// Rate control for HT code-blocks (EncodeParams::ht with byte or PSNR targets), checked from
// outside: files meet byte targets within [99.5 %, 100 %], decode in OpenJPEG and OpenJPH
// alike, meet PSNR targets, lose nothing to candidate skipping against coding every plane, and how
// far they fall behind our EBCOT encode at the same size is bounded and reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <thread>
#include <vector>

#include "codec/encoder/encoder.h"
#include "imageio/read.h"
#include "psnr.h"
#include "support/external_decode.h"
#include "support/scratch_dir.h"
#include "support/shared_assets.h"
#include "testimages/patterns.h"

namespace {

namespace fs = std::filesystem;
using Scratch = test_support::ScratchDir;
using test_support::decode_with;
using test_support::write_bytes;

// PSNR over every sample of every channel, peak 255.
double psnr_rgb(const imageio::Image& a, const imageio::Image& b) { return cli::psnr(a, b, 8).all_db; }

codec::EncodeParams at(double bytes, bool ht) {
  codec::EncodeParams p;
  p.lossless = false;
  p.ht = ht;
  p.dwt = codec::DwtDevice::Cpu;
  p.threads = 1;  // the cases run two at a time
  p.layers = {{codec::LayerTarget::Kind::Bytes, bytes}};
  return p;
}

// The Kodak photographs there are (../shared holds 16).
std::vector<int> photographs() {
  std::vector<int> found;
  for (int i = 1; i <= 24; ++i)
    if (fs::exists(test_support::kodak_photo(i))) found.push_back(i);
  return found;
}

// Runs case(k) for k < count on two threads: the CI machine's two cores, each encode on one.
void run_two_at_a_time(std::size_t count, const std::function<void(std::size_t)>& one_case) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t k = next++; k < count; k = next++) one_case(k);
  };
  std::thread other(worker);
  worker();
  other.join();
}

// Encodes and decodes with opj_decompress; PSNR over RGB.
struct Coded {
  std::size_t bytes = 0;
  double db = 0;
};

Coded encode_and_measure(const imageio::Image& img, const codec::EncodeParams& p, const Scratch& s,
                         const std::string& name, codec::EncodeReport* report = nullptr) {
  const auto bytes = codec::encode(codec::to_source_image(img, "image"), p, codec::FileFormat::Codestream, report);
  write_bytes(s / (name + ".j2k"), bytes);
  const imageio::Image back = decode_with("opj_decompress", s / (name + ".j2k"), s / (name + ".png"));
  return Coded{bytes.size(), psnr_rgb(img, back)};
}

constexpr double kRates[] = {0.25, 0.75, 2.0};

// The photographs at 0.25, 0.75 and 2 bpp: the HT file is within [99.5 %, 100 %] of its target,
// and its PSNR over RGB is compared with our EBCOT encode of the same target (decoded by
// opj_decompress). Measured on the 16 photographs with SigProp and MagRef points, the step's phase,
// raising and lowering (README, "HT rate control"): mean -0.43 / -0.47 / -0.50 dB, worst -0.78 /
// -0.75 / -0.86 dB at the three rates (photographs 1-4: mean -0.45 / -0.49 / -0.57, worst -0.57 /
// -0.55 / -0.86; before raising and lowering -0.47 / -0.55 / -0.61 on all 16, at the fixed step
// -0.54 / -0.64 / -0.67, cleanups alone -0.60 / -0.80 / -0.94). Issue 16 asks for 0.5 dB: the
// mean of all 16 at 0.75 bpp must keep it; the other bounds keep what is reached from regressing.
TEST(J2kHtRate, ByteTargetsOnTheKodakPhotographs) {
  const std::vector<int> photos = photographs();
  if (photos.empty())
    GTEST_SKIP() << "no Kodak photographs under " << (test_support::shared_dir() / "testimages" / "kodak");
  struct Case {
    int photo = 0;
    double bpp = 0;
    double target = 0;
    Coded ht, ebcot;
    std::string error;
  };
  std::vector<Case> cases;
  // Every photograph at 0.75 bpp, the first four at the other rates: the suite's time is bounded
  // (the README records all 16 at all three rates).
  for (int photo : photos)
    for (double bpp : kRates)
      if (bpp == 0.75 || photo <= 4) {
        Case c;
        c.photo = photo, c.bpp = bpp;
        cases.push_back(c);
      }
  run_two_at_a_time(cases.size(), [&](std::size_t k) {
    Case& c = cases[k];
    try {
      const imageio::Image img = imageio::read_image(test_support::kodak_photo(c.photo).string());
      c.target = std::floor(c.bpp * img.width * img.height / 8);
      Scratch s;
      c.ht = encode_and_measure(img, at(c.target, true), s, "ht");
      c.ebcot = encode_and_measure(img, at(c.target, false), s, "ebcot");
    } catch (const std::exception& e) {
      c.error = e.what();
    }
  });
  std::map<double, std::vector<double>> gaps;
  for (const Case& c : cases) {
    SCOPED_TRACE("photograph " + std::to_string(c.photo) + " at " + std::to_string(c.bpp) + " bpp");
    ASSERT_TRUE(c.error.empty()) << c.error;
    EXPECT_LE(static_cast<double>(c.ht.bytes), c.target);
    EXPECT_GE(static_cast<double>(c.ht.bytes), 0.995 * c.target);
    const double gap = c.ht.db - c.ebcot.db;
    std::printf("kodim%02d %.2f bpp: HT %zu bytes %.3f dB, EBCOT %zu bytes %.3f dB, HT - EBCOT %+.3f dB\n", c.photo,
                c.bpp, c.ht.bytes, c.ht.db, c.ebcot.bytes, c.ebcot.db, gap);
    EXPECT_GT(gap, -1.0);
    gaps[c.bpp].push_back(gap);
  }
  for (const auto& [bpp, list] : gaps) {
    double mean = 0;
    for (double g : list) mean += g / static_cast<double>(list.size());
    std::printf("%.2f bpp: HT - EBCOT mean %+.3f dB, worst %+.3f dB over %zu photographs\n", bpp, mean,
                *std::min_element(list.begin(), list.end()), list.size());
    const double bound = bpp == 0.75 ? -0.5 : bpp < 0.75 ? -0.55 : -0.65;
    EXPECT_GT(mean, bound) << "at " << bpp << " bpp";
  }
}

// The step's phase (EncodeParams::ht_step_from_target): an HT byte target of one tile at most 0.8
// bits per coefficient moves the base step by at most half an octave, and the file, decoded by
// OpenJPEG from the QCD marker's steps, lands on its target at about the fixed step's quality.
// Turned off, at 1 bit per coefficient, with a PSNR target, with two tiles or with EBCOT, the step is
// the one given.
TEST(J2kHtRate, StepPhaseMovesTheBaseStepHalfAnOctaveAtMost) {
  const imageio::Image img = testimages::generate(testimages::Pattern::Mix, 384, 256, 3, 8, false, 7);
  const double base = codec::EncodeParams{}.base_step;
  const double target = std::floor(0.75 * img.width * img.height / 8);
  Scratch s;
  codec::EncodeReport phased_report, fixed_report;
  const Coded phased = encode_and_measure(img, at(target, true), s, "phased", &phased_report);
  codec::EncodeParams fixed_params = at(target, true);
  fixed_params.ht_step_from_target = false;
  const Coded fixed = encode_and_measure(img, fixed_params, s, "fixed", &fixed_report);
  EXPECT_EQ(fixed_report.base_step, base);
  EXPECT_NE(phased_report.base_step, base);
  EXPECT_GE(phased_report.base_step, base / std::sqrt(2.0));
  EXPECT_LE(phased_report.base_step, base * std::sqrt(2.0));
  EXPECT_LE(static_cast<double>(phased.bytes), target);
  EXPECT_GE(static_cast<double>(phased.bytes), 0.995 * target);
  std::printf("generated 384x256 at 0.75 bpp: base step x%.4f, %.3f dB against %.3f dB\n",
              phased_report.base_step / base, phased.db, fixed.db);
  EXPECT_GT(phased.db, fixed.db - 0.25);

  auto step_of = [&](codec::EncodeParams p) {
    codec::EncodeReport report;
    codec::encode(codec::to_source_image(img, "image"), p, codec::FileFormat::Codestream, &report);
    return report.base_step;
  };
  EXPECT_EQ(step_of(at(std::floor(3.0 * img.width * img.height / 8), true)), base) << "1 bit per coefficient";
  codec::EncodeParams psnr = at(0, true);
  psnr.layers = {{codec::LayerTarget::Kind::Psnr, 32}};
  EXPECT_EQ(step_of(psnr), base) << "a PSNR target";
  codec::EncodeParams tiled = at(target, true);
  tiled.tile_width = tiled.tile_height = 128;
  EXPECT_EQ(step_of(tiled), base) << "six tiles";
  EXPECT_EQ(step_of(at(target, false)), base) << "EBCOT";
  // A base step near the sample range keeps its phase an octave finer rather than pass it: at
  // 0.03 bpp a base step of 0.75 wants the phase +0.44 octaves (1.016; measured 0.5082 with it).
  codec::EncodeParams coarse = at(std::floor(0.03 * img.width * img.height / 8), true);
  coarse.base_step = 0.75;
  const double coarse_step = step_of(coarse);
  EXPECT_GT(coarse_step, 0.75 / 2);
  EXPECT_LE(coarse_step, 1);
}

// The step's phase on the first four photographs at 0.75 bpp: their mean PSNR over RGB rises
// against the fixed step (by 0.107 dB when measured: +0.146, +0.118, +0.081, +0.082 dB; all 16
// at 0.25, 0.75 and 2 bpp: +0.076, +0.085 and +0.056 dB, README "The step's phase").
TEST(J2kHtRate, StepPhaseRaisesThePhotographsPsnr) {
  std::vector<int> photos = photographs();
  if (photos.size() > 4) photos.resize(4);
  if (photos.empty())
    GTEST_SKIP() << "no Kodak photographs under " << (test_support::shared_dir() / "testimages" / "kodak");
  std::vector<double> gain(photos.size());
  std::vector<std::string> errors(photos.size());
  run_two_at_a_time(photos.size(), [&](std::size_t k) {
    try {
      const imageio::Image img = imageio::read_image(test_support::kodak_photo(photos[k]).string());
      const double target = std::floor(0.75 * img.width * img.height / 8);
      Scratch s;
      codec::EncodeParams fixed = at(target, true);
      fixed.ht_step_from_target = false;
      gain[k] =
          encode_and_measure(img, at(target, true), s, "phased").db - encode_and_measure(img, fixed, s, "fixed").db;
    } catch (const std::exception& e) {
      errors[k] = e.what();
    }
  });
  double mean = 0;
  for (std::size_t k = 0; k < photos.size(); ++k) {
    ASSERT_TRUE(errors[k].empty()) << errors[k];
    std::printf("kodim%02d at 0.75 bpp: the step's phase %+.3f dB\n", photos[k], gain[k]);
    mean += gain[k] / static_cast<double>(photos.size());
  }
  EXPECT_GT(mean, 0.03);
}

// One photograph at the three rates through OpenJPEG and OpenJPH: both give the same picture (HT
// cleanups from many different planes, signalled by the missing MSBs, many followed by SigProp and
// MagRef passes in a refinement segment). Not Grok: grk_decompress 10.0.5 hands its HT block
// decoder the whole codeword as the cleanup segment with a refinement segment of length 0 (its
// t1 glue passes lengths2 = 0), so it fails on any block with refinement passes ("Error in HT
// block coder"); the cleanup-only streams of j2k_ht_test decode in it.
TEST(J2kHtRate, DecodesAlikeInOpenJpegAndOpenJph) {
  const fs::path file = test_support::kodak_photo(5);
  REQUIRE_SHARED_FILE(file);
  const imageio::Image img = imageio::read_image(file.string());
  for (double bpp : kRates) {
    SCOPED_TRACE(std::to_string(bpp) + " bpp");
    Scratch s;
    codec::EncodeParams p = at(std::floor(bpp * img.width * img.height / 8), true);
    p.threads = 2;
    write_bytes(s / "x.j2k", codec::encode(codec::to_source_image(img, "image"), p, codec::FileFormat::Codestream));
    const double opj = psnr_rgb(img, decode_with("opj_decompress", s / "x.j2k", s / "opj.png"));
    const double ojph = psnr_rgb(img, decode_with("ojph_expand", s / "x.j2k", s / "ojph.ppm"));
    EXPECT_GT(opj, bpp < 0.5 ? 20.0 : 25.0);
    EXPECT_NEAR(ojph, opj, 0.01);
  }
}

// PSNR targets through the rebuild-and-measure loop: the decoded PSNR lands in [target, target + 0.3].
// Without refinement passes (EncodeParams::ht_refinement false, j2kenc --ht-cleanup-only), the
// files decode in Grok too, alike in all three decoders, and within the byte target.
TEST(J2kHtRate, CleanupOnlyFilesDecodeInEveryDecoder) {
  const fs::path file = test_support::kodak_photo(5);
  REQUIRE_SHARED_FILE(file);
  const imageio::Image img = imageio::read_image(file.string());
  for (double bpp : kRates) {
    SCOPED_TRACE(std::to_string(bpp) + " bpp");
    Scratch s;
    const double target = std::floor(bpp * img.width * img.height / 8);
    codec::EncodeParams p = at(target, true);
    p.threads = 2;
    p.ht_refinement = false;
    const std::vector<std::uint8_t> bytes =
        codec::encode(codec::to_source_image(img, "image"), p, codec::FileFormat::Codestream);
    EXPECT_LE(static_cast<double>(bytes.size()), target);
    EXPECT_GE(static_cast<double>(bytes.size()), 0.995 * target);
    write_bytes(s / "x.j2k", bytes);
    const double opj = psnr_rgb(img, decode_with("opj_decompress", s / "x.j2k", s / "opj.png"));
    const double grk = psnr_rgb(img, decode_with("grk_decompress", s / "x.j2k", s / "grk.png"));
    const double ojph = psnr_rgb(img, decode_with("ojph_expand", s / "x.j2k", s / "ojph.ppm"));
    EXPECT_GT(opj, bpp < 0.5 ? 20.0 : 25.0);
    EXPECT_NEAR(grk, opj, 0.01);
    EXPECT_NEAR(ojph, opj, 0.01);
  }
}

TEST(J2kHtRate, PsnrTargetsLandJustAbove) {
  const fs::path file = test_support::kodak_photo(5);
  REQUIRE_SHARED_FILE(file);
  const imageio::Image img = imageio::read_image(file.string());
  for (double db : {30.0, 38.0}) {
    SCOPED_TRACE(std::to_string(db) + " dB");
    Scratch s;
    codec::EncodeParams p = at(0, true);
    p.threads = 2;
    p.layers = {{codec::LayerTarget::Kind::Psnr, db}};
    const Coded c = encode_and_measure(img, p, s, "x");
    std::printf("target %.0f dB: %.3f dB in %zu bytes\n", db, c.db, c.bytes);
    EXPECT_GE(c.db, db);
    EXPECT_LE(c.db, db + 0.3);
  }
}

// Coding only the cleanups near each block's estimated cut (and more where the allocation lands on
// the edge of what was coded) against coding every plane of every block: the same file, or where
// it differs a PSNR within 0.025 dB. Not identical by construction: a plane that is not on the hull
// of every plane can be on the hull of the three coded, and be chosen, where full coding takes a
// neighbour; and the greedy fill of the last bytes then differs. Measured on photographs 1-4 at
// the three rates, with SigProp and MagRef points: 8 of 12 files identical, the others -0.008 to
// +0.007 dB, before the step's phase (twentieth session); with it the bound was 0.01 dB. The
// phase puts many blocks' steps close to the threshold, where the prediction misses more of
// them: kodim03 at 0.25 bpp is 0.022 dB behind coding every plane (33.0074 against 33.0292 dB;
// three blocks refuse their top cleanup, the only one coded, where full coding takes the plane
// below), the others within 0.005 dB. Both are above what either gave at the fixed step.
TEST(J2kHtRate, CandidateSkippingIsNoWorseThanCodingEveryPlane) {
  std::vector<int> photos = photographs();
  if (photos.empty())
    GTEST_SKIP() << "no Kodak photographs under " << (test_support::shared_dir() / "testimages" / "kodak");
  photos.resize(std::min<std::size_t>(photos.size(), 4));
  struct Case {
    int photo = 0;
    double bpp = 0;
    bool identical = false;
    double skipped_db = 0, full_db = 0;
    std::string error;
  };
  std::vector<Case> cases;
  // Every photograph at 0.75 bpp, the first four at the other rates: the suite's time is bounded
  // (the README records all 16 at all three rates).
  for (int photo : photos)
    for (double bpp : kRates)
      if (bpp == 0.75 || photo <= 4) {
        Case c;
        c.photo = photo, c.bpp = bpp;
        cases.push_back(c);
      }
  run_two_at_a_time(cases.size(), [&](std::size_t k) {
    Case& c = cases[k];
    try {
      const imageio::Image img = imageio::read_image(test_support::kodak_photo(c.photo).string());
      codec::EncodeParams p = at(std::floor(c.bpp * img.width * img.height / 8), true);
      const auto source = codec::to_source_image(img, "image");
      const auto skipped = codec::encode(source, p, codec::FileFormat::Codestream);
      p.skip_passes = false;
      const auto full = codec::encode(source, p, codec::FileFormat::Codestream);
      c.identical = skipped == full;
      if (c.identical) return;
      Scratch s;
      write_bytes(s / "skipped.j2k", skipped);
      write_bytes(s / "full.j2k", full);
      c.skipped_db = psnr_rgb(img, decode_with("opj_decompress", s / "skipped.j2k", s / "skipped.png"));
      c.full_db = psnr_rgb(img, decode_with("opj_decompress", s / "full.j2k", s / "full.png"));
    } catch (const std::exception& e) {
      c.error = e.what();
    }
  });
  int identical = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE("photograph " + std::to_string(c.photo) + " at " + std::to_string(c.bpp) + " bpp");
    ASSERT_TRUE(c.error.empty()) << c.error;
    if (c.identical) {
      ++identical;
      continue;
    }
    std::printf("kodim%02d %.2f bpp: files differ: %.4f dB skipping, %.4f dB coding every plane\n", c.photo, c.bpp,
                c.skipped_db, c.full_db);
    EXPECT_GE(c.skipped_db, c.full_db - 0.025);
  }
  std::printf("candidate skipping gave the every-plane file in %d of %zu cases\n", identical, cases.size());
}

}  // namespace
