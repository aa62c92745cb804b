// Tests for the blending weights (thesis 3.4.3-3.4.5): the linear ramps of Figure 3.8 reproduced on
// the thesis' own /zung/ /gan/ example with values worked out by hand, equation 3.8 at sample points,
// the two-viseme limit of the vertex shader, expression overlay (equation 3.9), the blink channel,
// and the CSV / JSON / Oculus outputs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "performer/blink_generator.h"
#include "performer/viseme_error.h"
#include "performer/viseme_library.h"
#include "performer/viseme_timing.h"
#include "performer/weights_curves.h"
#include "performer/weights_expression.h"
#include "performer/weights_oculus.h"
#include "performer/weights_input.h"
#include "performer/weights_output.h"
#include "performer/weights_track.h"
#include "performer/weights_visemes.h"

using performer::DominanceWindow;
using performer::TimedViseme;
using performer::WeightCurve;
using performer::WeightParams;

namespace {

constexpr int kVisemes = 16;
// Thesis viseme IDs used below.
constexpr int kAA = 3, kEH = 2, kO = 4, kUH = 5, kM = 8, kN = 9, kNG = 10, kS = 13, kK = 15, kIY = 1;

// /zung/ /gan/ ("centre", thesis 3.4.3): zung 0.33 s split 0.25 / 0.375 / 0.375 into z, u, ng;
// gan 0.30 s likewise into g, a, n. Written out rather than computed, so this test stands alone.
const std::vector<TimedViseme> kZungGan = {
    {0.0, 0.0825, kS},        // z
    {0.0825, 0.12375, kO},    // u (nucleus)
    {0.20625, 0.12375, kNG},  // ng (coda)
    {0.33, 0.075, kK},        // g
    {0.405, 0.1125, kAA},     // a
    {0.5175, 0.1125, kN},     // n (coda)
};

std::vector<float> weights_at(const std::vector<TimedViseme>& seq, const WeightParams& p, double t) {
  std::vector<float> out(kVisemes);
  const std::vector<double> times{t};
  performer::viseme_weight_frames(seq, p, times, kVisemes, out);
  return out;
}

// Expected weights: every ID not listed must be 0.
void expect_weights(const std::vector<float>& got, std::vector<std::pair<int, double>> want, double t) {
  std::vector<double> full(kVisemes, 0.0);
  for (const auto& [id, w] : want) full[static_cast<std::size_t>(id)] = w;
  for (int id = 0; id < kVisemes; ++id)
    EXPECT_NEAR(got[static_cast<std::size_t>(id)], full[static_cast<std::size_t>(id)], 1e-6)
        << "viseme " << id << " at t = " << t;
}

TEST(LinearWeights, Figure3_8OnZungGan) {
  const WeightParams p;  // linear, lead-in 0.1 s
  // Before z: it rises over the lead-in.
  expect_weights(weights_at(kZungGan, p, -0.15), {}, -0.15);
  expect_weights(weights_at(kZungGan, p, -0.05), {{kS, 0.5}}, -0.05);
  // "Each viseme starts with a unity weight at its start instant, and linearly decreases to zero
  // weight at its end point", while the next one rises (Figure 3.7).
  expect_weights(weights_at(kZungGan, p, 0.0), {{kS, 1.0}}, 0.0);
  expect_weights(weights_at(kZungGan, p, 0.04125), {{kS, 0.5}, {kO, 0.5}}, 0.04125);
  expect_weights(weights_at(kZungGan, p, 0.0825), {{kO, 1.0}}, 0.0825);
  expect_weights(weights_at(kZungGan, p, 0.144375), {{kO, 0.5}, {kNG, 0.5}}, 0.144375);
  // Across the syllable boundary: ng falls over (0.20625, 0.33) while g rises.
  expect_weights(weights_at(kZungGan, p, 0.30), {{kNG, 0.03 / 0.12375}, {kK, 0.09375 / 0.12375}}, 0.30);
  expect_weights(weights_at(kZungGan, p, 0.33), {{kK, 1.0}}, 0.33);
  expect_weights(weights_at(kZungGan, p, 0.37), {{kK, 0.035 / 0.075}, {kAA, 0.04 / 0.075}}, 0.37);
  // The last viseme falls to zero at its end, with nothing after it.
  expect_weights(weights_at(kZungGan, p, 0.6), {{kN, 0.03 / 0.1125}}, 0.6);
  expect_weights(weights_at(kZungGan, p, 0.63), {}, 0.63);
  expect_weights(weights_at(kZungGan, p, 0.7), {}, 0.7);
}

TEST(LinearWeights, NeighboursSumToOneInsideAWord) {
  const WeightParams p;
  for (double t = 0.0; t < 0.5175; t += 0.001) {
    const auto w = weights_at(kZungGan, p, t);
    double sum = 0.0;
    for (float x : w) sum += x;
    EXPECT_NEAR(sum, 1.0, 1e-5) << "t = " << t;
  }
}

TEST(LinearWeights, GapsReturnToNeutralAndLeadInStopsAtThePreviousEnd) {
  // A at [0, 0.2]; B after a 0.05 s gap: its lead-in (0.1) would reach back into A, so it starts at
  // A's end. C after a long gap rises over the full lead-in.
  const std::vector<TimedViseme> seq = {{0.0, 0.2, kAA}, {0.25, 0.2, kM}, {1.0, 0.2, kUH}};
  const WeightParams p;
  expect_weights(weights_at(seq, p, 0.2), {}, 0.2);
  expect_weights(weights_at(seq, p, 0.225), {{kM, 0.5}}, 0.225);
  expect_weights(weights_at(seq, p, 0.5), {}, 0.5);
  expect_weights(weights_at(seq, p, 0.95), {{kUH, 0.5}}, 0.95);
}

TEST(LinearWeights, RepeatedVisemeHoldsItsShape) {
  // m then b: both M. Their ramps sum, so the lips stay shut instead of opening halfway between.
  const std::vector<TimedViseme> seq = {{0.0, 0.1, kM}, {0.1, 0.1, kM}, {0.2, 0.1, kAA}};
  expect_weights(weights_at(seq, WeightParams{}, 0.05), {{kM, 1.0}}, 0.05);
  expect_weights(weights_at(seq, WeightParams{}, 0.15), {{kM, 0.5}, {kAA, 0.5}}, 0.15);
}

TEST(KeepStrongest, KeepsTheHeaviestLowerIndexOnTies) {
  std::vector<float> w = {0.2f, 0.9f, 0.5f, 0.9f};
  performer::keep_strongest(w, 2);
  EXPECT_EQ(w, (std::vector<float>{0.0f, 0.9f, 0.0f, 0.9f}));
  w = {0.5f, 0.5f, 0.5f};
  performer::keep_strongest(w, 2);
  EXPECT_EQ(w, (std::vector<float>{0.5f, 0.5f, 0.0f}));
  w = {0.0f, 0.3f, 0.0f};
  performer::keep_strongest(w, 2);
  EXPECT_EQ(w, (std::vector<float>{0.0f, 0.3f, 0.0f}));
}

TEST(TwoVisemeLimit, ThreeOverlappingVisemesKeepTheTwoStrongest) {
  // Hand-typed keyframes that overlap: at t = 0.25 the ramps are A 0.75, B 0.75/0.9, C 0.75/0.8.
  const std::vector<TimedViseme> seq = {{0.0, 1.0, kEH}, {0.1, 0.9, kAA}, {0.2, 0.8, kO}};
  WeightParams all;
  all.max_visemes = kVisemes;
  expect_weights(weights_at(seq, all, 0.25), {{kEH, 0.75}, {kAA, 0.75 / 0.9}, {kO, 0.75 / 0.8}}, 0.25);
  expect_weights(weights_at(seq, WeightParams{}, 0.25), {{kAA, 0.75 / 0.9}, {kO, 0.75 / 0.8}}, 0.25);
}

// Random sequences with overlaps, gaps and repeats: never more than two non-zero weights, all in
// [0, 1], under both curves; and without the limit the same input does produce frames with more.
TEST(TwoVisemeLimit, HoldsOnRandomSequences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(0.0, 0.15), length(0.0, 0.4);
  std::uniform_int_distribution<int> id(0, kVisemes - 1);
  std::vector<TimedViseme> seq;
  double t = 0.0;
  for (int i = 0; i < 200; ++i) {
    t += step(rng);
    seq.push_back({t, length(rng), id(rng)});
  }
  std::vector<double> times;
  for (double s = -0.2; s < t + 0.5; s += 0.0037) times.push_back(s);
  for (WeightCurve curve : {WeightCurve::linear, WeightCurve::exponential}) {
    WeightParams p;
    p.curve = curve;
    p.time_scale = 0.1;
    std::vector<float> out(times.size() * kVisemes);
    performer::viseme_weight_frames(seq, p, times, kVisemes, out);
    for (std::size_t f = 0; f < times.size(); ++f) {
      int nonzero = 0;
      for (int v = 0; v < kVisemes; ++v) {
        const float w = out[f * kVisemes + static_cast<std::size_t>(v)];
        EXPECT_GE(w, 0.0f);
        EXPECT_LE(w, 1.0f);
        nonzero += w != 0.0f;
      }
      ASSERT_LE(nonzero, 2) << "t = " << times[f];
    }
    p.max_visemes = kVisemes;
    performer::viseme_weight_frames(seq, p, times, kVisemes, out);
    int most = 0;
    for (std::size_t f = 0; f < times.size(); ++f)
      most = std::max<int>(most, static_cast<int>(std::count_if(out.begin() + static_cast<long>(f * kVisemes),
                                                                out.begin() + static_cast<long>((f + 1) * kVisemes),
                                                                [](float w) { return w != 0.0f; })));
    EXPECT_GT(most, 2) << "the input overlaps enough for the limit to matter";
  }
}

// Equation 3.8: alpha(t) = lambda * exp(-|t - (t_start + t_dur / 2)|), exponent divided by
// time_scale (1 s: the equation as printed).
double eq3_8(double t, double start, double dur, double lambda, double scale) {
  return lambda * std::exp(-std::fabs(t - (start + dur / 2)) / scale);
}

TEST(ExponentialWeights, FollowEquation3_8AtSamplePoints) {
  // A, B, C touch; D follows a gap.
  const std::vector<TimedViseme> seq = {{0.0, 0.2, kAA}, {0.2, 0.3, kEH}, {0.5, 0.2, kM}, {1.0, 0.2, kUH}};
  for (double scale : {1.0, 0.05}) {
    WeightParams p;
    p.curve = WeightCurve::exponential;
    p.lambda = 0.8;
    p.time_scale = scale;
    const auto a = [&](double t) { return eq3_8(t, 0.0, 0.2, 0.8, scale); };
    const auto b = [&](double t) { return eq3_8(t, 0.2, 0.3, 0.8, scale); };
    const auto c = [&](double t) { return eq3_8(t, 0.5, 0.2, 0.8, scale); };
    const auto d = [&](double t) { return eq3_8(t, 1.0, 0.2, 0.8, scale); };
    // A's window: lead-in from -0.1, to B's centre 0.35. B: A's centre 0.1 to C's 0.6. C: 0.35 to
    // its end 0.7 (nothing touches it after). D: lead-in 0.9 to its end 1.2.
    expect_weights(weights_at(seq, p, -0.15), {}, -0.15);
    expect_weights(weights_at(seq, p, -0.05), {{kAA, a(-0.05)}}, -0.05);
    expect_weights(weights_at(seq, p, 0.05), {{kAA, a(0.05)}}, 0.05);
    expect_weights(weights_at(seq, p, 0.1), {{kAA, 0.8}, {kEH, b(0.1)}}, 0.1);
    expect_weights(weights_at(seq, p, 0.2), {{kAA, a(0.2)}, {kEH, b(0.2)}}, 0.2);
    expect_weights(weights_at(seq, p, 0.45), {{kEH, b(0.45)}, {kM, c(0.45)}}, 0.45);
    expect_weights(weights_at(seq, p, 0.65), {{kM, c(0.65)}}, 0.65);
    expect_weights(weights_at(seq, p, 0.8), {}, 0.8);
    expect_weights(weights_at(seq, p, 0.95), {{kUH, d(0.95)}}, 0.95);
    expect_weights(weights_at(seq, p, 1.1), {{kUH, 0.8}}, 1.1);
    expect_weights(weights_at(seq, p, 1.25), {}, 1.25);
  }
  EXPECT_NEAR(performer::exponential_weight(0.3, 0.0, 0.2, 1.0, 1.0), std::exp(-0.2), 1e-12);
}

TEST(WeightParams, BadParametersAndSequencesAreRejected) {
  WeightParams p;
  p.lambda = 1.5;
  EXPECT_THROW(weights_at(kZungGan, p, 0.0), std::invalid_argument);
  p = {};
  p.time_scale = 0.0;
  EXPECT_THROW(weights_at(kZungGan, p, 0.0), std::invalid_argument);
  p = {};
  p.max_visemes = 0;
  EXPECT_THROW(weights_at(kZungGan, p, 0.0), std::invalid_argument);
  EXPECT_THROW(weights_at({{0.2, 0.1, kAA}, {0.1, 0.1, kM}}, WeightParams{}, 0.0), std::invalid_argument);
  EXPECT_THROW(weights_at({{0.0, -0.1, kAA}}, WeightParams{}, 0.0), std::invalid_argument);
  EXPECT_THROW(weights_at({{0.0, 0.1, kVisemes}}, WeightParams{}, 0.0), std::invalid_argument);
}

TEST(RampWeight, Steps) {
  EXPECT_DOUBLE_EQ(performer::ramp_weight(DominanceWindow{1.0, 1.0, 2.0}, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(performer::ramp_weight(DominanceWindow{1.0, 1.0, 2.0}, 0.999), 0.0);
  EXPECT_DOUBLE_EQ(performer::ramp_weight(DominanceWindow{0.0, 1.0, 1.0}, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(performer::ramp_weight(DominanceWindow{0.0, 1.0, 1.0}, 1.001), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Expression overlay (equation 3.9).

const char* kExpressions =
    "# smile comes and goes; worry steps up; surprise held throughout\n"
    "0    smile    0\n"
    "1    smile    1\n"
    "2    smile    0.5\n"
    "0.5  worry    0.2\n"
    "0.5  worry    0.6   # a step\n"
    "3    surprise 0.1\n";

TEST(ExpressionOverlay, InterpolatesHoldsAndSteps) {
  const auto keys = performer::parse_expression_keys(kExpressions, "e.txt");
  ASSERT_EQ(keys.size(), 6u);
  EXPECT_EQ(keys[4].line, 6);
  EXPECT_EQ(performer::expression_names(keys), (std::vector<std::string>{"smile", "worry", "surprise"}));
  EXPECT_NEAR(performer::expression_weight(keys, "smile", 0.25), 0.25, 1e-12);
  EXPECT_NEAR(performer::expression_weight(keys, "smile", 1.5), 0.75, 1e-12);
  EXPECT_NEAR(performer::expression_weight(keys, "smile", 9.0), 0.5, 1e-12) << "holds its last key";
  EXPECT_NEAR(performer::expression_weight(keys, "worry", 0.1), 0.2, 1e-12) << "holds its first key";
  EXPECT_NEAR(performer::expression_weight(keys, "worry", 0.5), 0.6, 1e-12) << "the later of two keys at once";
  EXPECT_NEAR(performer::expression_weight(keys, "surprise", 0.0), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(performer::expression_weight(keys, "anger", 1.0), 0.0);

  // Two expression streams: at t = 1 smile 1, worry 0.6, surprise 0.1 -> surprise dropped.
  const auto names = performer::expression_names(keys);
  std::vector<float> out(3);
  performer::expression_weights_at(keys, names, 1.0, 2, out);
  EXPECT_EQ(out, (std::vector<float>{1.0f, 0.6f, 0.0f}));

  const auto constant = performer::constant_expression("smile", 0.3);
  EXPECT_NEAR(performer::expression_weight(constant, "smile", 12.0), 0.3, 1e-12);
  EXPECT_THROW(performer::constant_expression("smile", 1.2), std::invalid_argument);
}

void expect_expression_error(const std::string& text, int line, const std::string& words) {
  try {
    performer::parse_expression_keys(text, "e.txt");
    FAIL() << "expected an error for:\n" << text;
  } catch (const performer::VisemeDataError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("e.txt:" + std::to_string(line) + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(ExpressionOverlay, MalformedLinesNameTheirLine) {
  expect_expression_error("0 smile\n", 1, "expected 3 fields");
  expect_expression_error("0 smile 0\nx smile 1\n", 2, "time 'x'");
  expect_expression_error("0 smile 1.5\n", 1, "outside [0, 1]");
  expect_expression_error("1 smile 0\n0 worry 1\n0.5 smile 1\n", 3, "earlier than its key on line 1");
}

// ---------------------------------------------------------------------------------------------
// Blinks.

// First two blink starts for seed 1 and the default parameters, recorded from this implementation.
constexpr double kGoldenFirst = 1.4311838114807747;
constexpr double kGoldenSecond = 2.8711449957481512;

TEST(Blinks, DeterministicForASeed) {
  performer::BlinkParams p;
  p.seed = 42;
  const auto a = performer::generate_blinks(p, 0.0, 120.0);
  const auto b = performer::generate_blinks(p, 0.0, 120.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].start, b[i].start);
  // Roughly one blink per mean interval, never closer than the minimum.
  EXPECT_GT(a.size(), 15u);
  EXPECT_LT(a.size(), 50u);
  for (std::size_t i = 1; i < a.size(); ++i) EXPECT_GE(a[i].start - a[i - 1].start, p.min_interval);
  p.seed = 43;
  const auto c = performer::generate_blinks(p, 0.0, 120.0);
  EXPECT_NE(a.front().start, c.front().start);
  // The sequence is ours (mt19937_64, whose output the standard fixes, through our own
  // conversion), so these values hold on every platform.
  p.seed = 1;
  const auto golden = performer::generate_blinks(p, 0.0, 10.0);
  ASSERT_GE(golden.size(), 2u);
  EXPECT_NEAR(golden[0].start, kGoldenFirst, 1e-9);
  EXPECT_NEAR(golden[1].start, kGoldenSecond, 1e-9);
}

TEST(Blinks, CloseFastOpenSlowly) {
  const std::vector<performer::Blink> blinks = {{1.0, 0.25}, {5.0, 0.25}};
  EXPECT_DOUBLE_EQ(performer::blink_weight(blinks, 0.4, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(performer::blink_weight(blinks, 0.4, 1.0), 0.0);
  EXPECT_NEAR(performer::blink_weight(blinks, 0.4, 1.05), 0.5, 1e-12);
  EXPECT_NEAR(performer::blink_weight(blinks, 0.4, 1.1), 1.0, 1e-12);
  EXPECT_NEAR(performer::blink_weight(blinks, 0.4, 1.175), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(performer::blink_weight(blinks, 0.4, 1.25), 0.0);
  EXPECT_NEAR(performer::blink_weight(blinks, 0.4, 5.1), 1.0, 1e-12);
  performer::BlinkParams bad;
  bad.min_interval = 0.1;
  EXPECT_THROW(performer::generate_blinks(bad, 0.0, 1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// The assembled track and its outputs.

const performer::VisemeSet& viseme_set() {
  static const performer::VisemeLibrary lib = performer::VisemeLibrary::load_default();
  return lib.visemes();
}

TEST(WeightTrack, FramesHoldVisemesExpressionsAndBlink) {
  EXPECT_EQ(performer::frame_times(0.0, 1.0, 30.0).size(), 31u);
  EXPECT_EQ(performer::frame_times(0.0, 0.63, 10.0).size(), 7u);

  const auto smile = performer::constant_expression("smile", 0.3);
  performer::TrackOptions options;
  options.fps = 10.0;
  options.blink_params.seed = 3;
  options.blink_params.min_interval = 0.25;
  options.blink_params.mean_interval = 0.3;
  const performer::WeightTrack track = performer::build_weight_track(kZungGan, viseme_set(), smile, options);
  ASSERT_EQ(track.channel_count(), 18u);
  EXPECT_EQ(track.channels.front(), "closed");
  EXPECT_EQ(track.channels[16], "smile");
  EXPECT_EQ(track.channels[17], "blink");
  EXPECT_EQ(track.viseme_channels, 16);
  ASSERT_EQ(track.frame_count(), 7u);
  const auto f3 = track.frame(3);  // t = 0.3, as in Figure3_8OnZungGan
  EXPECT_NEAR(f3[kNG], 0.03 / 0.12375, 1e-6);
  EXPECT_NEAR(f3[kK], 0.09375 / 0.12375, 1e-6);
  EXPECT_NEAR(f3[16], 0.3, 1e-6);
  bool blinked = false;
  for (std::size_t f = 0; f < track.frame_count(); ++f) blinked = blinked || track.frame(f)[17] > 0.0f;
  EXPECT_TRUE(blinked) << "blinks every 0.25-0.3 s must show in 0.63 s at 10 fps";

  const auto bad = performer::constant_expression("AA", 0.3);
  EXPECT_THROW(performer::build_weight_track(kZungGan, viseme_set(), bad, options), std::invalid_argument);
}

TEST(WeightTrack, CsvAndJson) {
  performer::TrackOptions options;
  options.fps = 10.0;
  options.blink = false;
  const auto smile = performer::constant_expression("smile", 0.3);
  const performer::WeightTrack track = performer::build_weight_track(kZungGan, viseme_set(), smile, options);

  std::ostringstream csv;
  performer::write_weights_csv(csv, track);
  std::istringstream lines(csv.str());
  std::string header, row0, row3;
  std::getline(lines, header);
  std::getline(lines, row0);
  std::getline(lines, row3);
  std::getline(lines, row3);
  std::getline(lines, row3);
  EXPECT_EQ(header, "time,closed,IY,EH,AA,O,UH,Y,L,M,N,NG,F,TH,S,SH,K,smile");
  EXPECT_EQ(row0, "0,0,0,0,0,0,0,0,0,0,0,0,0,0,1,0,0,0.3");
  EXPECT_EQ(row3, "0.3,0,0,0,0,0,0,0,0,0,0,0.242424,0,0,0,0,0.757576,0.3");
  const std::string text = csv.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 8);

  std::ostringstream json;
  performer::write_weights_json(json, track);
  const std::string j = json.str();
  EXPECT_EQ(j.rfind("{\n  \"fps\": 10,\n  \"channels\": [\"closed\", \"IY\"", 0), 0u) << j;
  EXPECT_NE(j.find("\"time\": [0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]"), std::string::npos) << j;
  EXPECT_NE(j.find("\"S\": [1, 0, 0, 0, 0, 0, 0]"), std::string::npos) << j;
  EXPECT_NE(j.find("\"smile\": [0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 0.3]"), std::string::npos) << j;
}

// What write_weights_csv writes reads back: same channels, viseme count, times, fps and weights
// (to the six decimals written). Malformed files name their line.
TEST(WeightTrack, CsvReadsBack) {
  performer::TrackOptions options;
  options.fps = 25.0;
  options.blink_params.seed = 5;
  const auto smile = performer::constant_expression("smile", 0.3);
  const performer::WeightTrack track = performer::build_weight_track(kZungGan, viseme_set(), smile, options);
  std::ostringstream csv;
  performer::write_weights_csv(csv, track);
  const performer::WeightTrack back = performer::parse_weights_csv(csv.str(), "w.csv", viseme_set());
  EXPECT_EQ(back.channels, track.channels);
  EXPECT_EQ(back.viseme_channels, track.viseme_channels);
  EXPECT_NEAR(back.fps, 25.0, 1e-6);
  ASSERT_EQ(back.frame_count(), track.frame_count());
  for (std::size_t f = 0; f < track.frame_count(); ++f) {
    EXPECT_NEAR(back.times[f], track.times[f], 1e-6);
    for (std::size_t c = 0; c < track.channel_count(); ++c) EXPECT_NEAR(back.frame(f)[c], track.frame(f)[c], 1e-6);
  }

  auto line_of_error = [](const std::string& text) {
    try {
      performer::parse_weights_csv(text, "w.csv", viseme_set());
    } catch (const performer::VisemeDataError& e) {
      return e.line();
    }
    return -1;
  };
  EXPECT_EQ(line_of_error("t,AA\n0,1\n"), 1);                // first column not "time"
  EXPECT_EQ(line_of_error("time,AA,AA\n0,1,1\n"), 1);        // repeated channel
  EXPECT_EQ(line_of_error("time,AA\n0,1\n0.1,0.5,2\n"), 3);  // field count
  EXPECT_EQ(line_of_error("time,AA\n0,1\n0.1,x\n"), 3);      // not a number
  EXPECT_EQ(line_of_error("time,AA\n0,1\n\n0,1\n"), 4);      // time not increasing
  EXPECT_EQ(line_of_error("time,AA\n0,1.5\n"), 2);           // outside [0, 1]
  EXPECT_EQ(line_of_error("time,\"A\n"), 1);                 // unterminated quote
  EXPECT_EQ(line_of_error("time,AA\n"), 0);                  // no frames
  EXPECT_EQ(line_of_error(""), 0);                           // no header
  const auto quoted =
      performer::parse_weights_csv("time,\"AA\",\"my, \"\"odd\"\" one\"\r\n0,1,0.5\r\n", "q.csv", viseme_set());
  EXPECT_EQ(quoted.channels, (std::vector<std::string>{"AA", "my, \"odd\" one"}));
  EXPECT_EQ(quoted.viseme_channels, 1);
}

TEST(WeightTrack, OculusFold) {
  const performer::VisemeSet& set = viseme_set();
  std::vector<float> w(16, 0.0f), out(15);
  w[kNG] = 0.4f;  // NG and K are both Oculus kk
  w[kK] = 0.5f;
  w[kIY] = 0.7f;  // IY and Y are both ih
  w[6] = 0.6f;
  performer::fold_to_oculus(w, set, out);
  const auto at = [&](std::string_view name) {
    return out[static_cast<std::size_t>(
        std::find(performer::kOculusVisemes.begin(), performer::kOculusVisemes.end(), name) -
        performer::kOculusVisemes.begin())];
  };
  EXPECT_NEAR(at("kk"), 0.9f, 1e-6);
  EXPECT_FLOAT_EQ(at("ih"), 1.0f) << "clamped";
  EXPECT_FLOAT_EQ(at("aa"), 0.0f);

  performer::TrackOptions options;
  options.fps = 10.0;
  options.blink = false;
  const auto track =
      performer::build_weight_track(kZungGan, set, performer::constant_expression("smile", 0.3), options);
  const auto oculus = performer::oculus_track(track, set);
  ASSERT_EQ(oculus.channel_count(), 16u);
  EXPECT_EQ(oculus.channels[0], "sil");
  EXPECT_EQ(oculus.channels[15], "smile");
  EXPECT_NEAR(oculus.frame(3)[5], 1.0f, 1e-6) << "kk = NG + K at t = 0.3";
  EXPECT_NEAR(oculus.frame(0)[7], 1.0f, 1e-6) << "SS = S at t = 0";
}

}  // namespace
