// The wavelet applications of thesis 4.7 (wavelet_apps) against independent computations done here:
// the transform by the CPU backend, the band operation written out in the test over band_rect, the
// inverse; and the GPU engine (coefficients kept on the GPU) against the CPU within 1e-4 of the
// range. GPU cases run on whatever context the GL layer makes (llvmpipe in CI) and skip, saying why,
// when none can be made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "dwt/band_operation.h"
#include "dwt_cpu/cpu_backend.h"
#include "glcontext/error.h"
#include "support/scratch_dir.h"
#include "testimages/patterns.h"
#include "wavelet_apps/band_spec.h"
#include "wavelet_apps/control_net.h"
#include "wavelet_apps/engine.h"
#include "wavelet_apps/image_apps.h"
#include "wavelet_apps/image_planes.h"

namespace wa = wavelet_apps;

namespace {

constexpr float kRange = 255.0f;

wa::WaveletEngine& cpu_engine() {
  static auto engine = wa::make_cpu_engine(2);
  return *engine;
}

// The GPU engine, or nullptr with the reason when no GL context can be created here.
wa::WaveletEngine* gpu_engine(std::string& why) {
  static std::string failure;
  static std::unique_ptr<wa::WaveletEngine> engine = [] {
    auto e = wa::make_gpu_engine(glc::Platform::Auto);
    try {
      std::printf("GL renderer: %s\n", e->prepare().c_str());
    } catch (const std::exception& error) {
      failure = error.what();
      return std::unique_ptr<wa::WaveletEngine>();
    }
    return e;
  }();
  why = failure;
  return engine.get();
}

#define REQUIRE_GPU(engine_var)                            \
  std::string gpu_failure;                                 \
  wa::WaveletEngine* engine_var = gpu_engine(gpu_failure); \
  if (!engine_var) GTEST_SKIP() << "no GL context can be created here: " << gpu_failure

imageio::Image photo_like(int width, int height, int channels = 3) {
  return testimages::generate(testimages::Pattern::Mix, width, height, channels, 8);
}

dwt::DwtParams params(int levels) {
  dwt::DwtParams p;
  p.levels = levels;
  return p;
}

float max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  float worst = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

// The reference: CPU forward, `factor(band)` applied here band by band, CPU inverse.
template <class Factor>
std::vector<float> reference_edit(std::vector<float> plane, int width, int height, const dwt::DwtParams& p,
                                  Factor&& factor) {
  dwt_cpu::CpuBackend cpu(2);
  const auto span = dwt::make_span(plane.data(), width, height);
  cpu.forward(span, p);
  const auto levels = dwt::decomposition(width, height, p.origin, p.levels);
  for (int level = 1; level <= p.levels; ++level)
    for (auto o : {dwt::Orientation::HL, dwt::Orientation::LH, dwt::Orientation::HH}) {
      const dwt::LayoutRect r = dwt::band_rect(levels, level, o);
      for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x) span.at(x, y) *= factor(level, o);
    }
  const dwt::LayoutRect ll = dwt::band_rect(levels, p.levels, dwt::Orientation::LL);
  for (int y = 0; y < ll.height; ++y)
    for (int x = 0; x < ll.width; ++x) span.at(x, y) *= factor(0, dwt::Orientation::LL);
  cpu.inverse(span, p);
  return plane;
}

// ---- band specs -------------------------------------------------------------------------------

TEST(BandSpec, ParsesChannelsLevelsOrientationsAndOperations) {
  const std::vector<std::string> ycc = {"Y", "Cb", "Cr"};
  const auto a = wa::parse_scale_spec("Y:1:*=1.8", ycc, 5);
  EXPECT_EQ(a.where.channel, 0);
  EXPECT_EQ(a.where.level, 1);
  EXPECT_FALSE(a.where.orientation);
  EXPECT_FLOAT_EQ(a.factor, 1.8f);
  const auto b = wa::parse_scale_spec("2:HH=zero", ycc, 5);
  EXPECT_EQ(b.where.channel, -1);
  EXPECT_EQ(b.where.level, 2);
  EXPECT_EQ(b.where.orientation, dwt::Orientation::HH);
  EXPECT_EQ(b.factor, 0.0f);
  EXPECT_TRUE(wa::parse_scale_spec("Cb:LL=keep", ycc, 5).where.lowest);
  EXPECT_TRUE(wa::parse_scale_spec("*=0.5", ycc, 5).where.every_band);
  EXPECT_EQ(wa::parse_rule_spec("Y:*:HL=max", ycc, 5).rule, dwt::BandRule::LargerMagnitude);
}

TEST(BandSpec, RejectsBadSpecsNamingThem) {
  const std::vector<std::string> rgb = {"R", "G", "B"};
  for (const char* bad : {"Q:1:HH=2", "1:XY=2", "6:HH=2", "1:HH=abc", "1:HH", "LX=1", "0:HH=1", "1:HH=inf"}) {
    try {
      wa::parse_scale_spec(bad, rgb, 5);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const wa::AppError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(wa::parse_rule_spec("Y:1:*=bigger", {{"Y"}}, 3), wa::AppError);
}

// ---- edit ---------------------------------------------------------------------------------------

TEST(Edit, AllFactorsOneReproducesTheInputOnTheCpu) {
  const imageio::Image image = photo_like(96, 80);
  for (const auto space : {wa::ColourSpace::Rgb, wa::ColourSpace::YCbCr}) {
    wa::EditSettings s;
    s.params = params(4);
    s.space = space;
    s.bands = {wa::parse_scale_spec("*=1", wa::channel_names(3, space), 4)};
    const imageio::Image floats = wa::from_planes(wa::edit_planes(image, s, cpu_engine()), space);
    EXPECT_LT(max_difference(floats.pixels, image.pixels), 1e-3f);           // float rounding on 0..255
    EXPECT_EQ(wa::edit_image(image, s, cpu_engine()).pixels, image.pixels);  // exact after rounding
  }
}

TEST(Edit, AllFactorsOneReproducesTheInputOnTheGpu) {
  REQUIRE_GPU(gpu);
  const imageio::Image image = photo_like(96, 80);
  wa::EditSettings s;
  s.params = params(4);
  s.space = wa::ColourSpace::YCbCr;
  const imageio::Image floats = wa::from_planes(wa::edit_planes(image, s, *gpu), s.space);
  EXPECT_LT(max_difference(floats.pixels, image.pixels), 1e-2f);
  EXPECT_EQ(wa::edit_image(image, s, *gpu).pixels, image.pixels);
}

TEST(Edit, ScalingMatchesTheBandOperationDoneOnTheCoefficientsAndGpuEqualsCpu) {
  const int W = 120, H = 72, L = 3;
  const imageio::Image image = photo_like(W, H);
  wa::EditSettings s;
  s.params = params(L);
  s.space = wa::ColourSpace::YCbCr;
  const auto names = wa::channel_names(3, s.space);
  for (const char* spec : {"Y:1:*=1.8", "Y:2:HH=0", "Cb:LL=0.5", "*:HL=zero", "Cr:3:LH=-2"})
    s.bands.push_back(wa::parse_scale_spec(spec, names, L));
  // Written out independently: the factor of each band of each channel.
  auto factor = [](int channel, int level, dwt::Orientation o) {
    float f = 1.0f;
    if (channel == 0 && level == 1) f = 1.8f;
    if (channel == 0 && level == 2 && o == dwt::Orientation::HH) f = 0.0f;
    if (channel == 1 && o == dwt::Orientation::LL) f = 0.5f;
    if (o == dwt::Orientation::HL) f = 0.0f;
    if (channel == 2 && level == 3 && o == dwt::Orientation::LH) f = -2.0f;
    return f;
  };
  const wa::Planes input = wa::to_planes(image, s.space);
  const wa::Planes cpu = wa::edit_planes(image, s, cpu_engine());
  for (int c = 0; c < 3; ++c) {
    const auto expected = reference_edit(input.planes[static_cast<std::size_t>(c)], W, H, s.params,
                                         [&](int level, dwt::Orientation o) { return factor(c, level, o); });
    EXPECT_LT(max_difference(cpu.planes[static_cast<std::size_t>(c)], expected), 1e-4f * kRange) << "channel " << c;
  }
  REQUIRE_GPU(gpu);
  const wa::Planes on_gpu = wa::edit_planes(image, s, *gpu);
  for (std::size_t c = 0; c < 3; ++c)
    EXPECT_LT(max_difference(on_gpu.planes[c], cpu.planes[c]), 1e-4f * kRange) << "channel " << c;
}

// ---- combine ------------------------------------------------------------------------------------

TEST(Combine, FollowsTheThesisRulesAndGpuEqualsCpu) {
  const int W = 96, H = 96, L = 3;
  const imageio::Image base = photo_like(W, H);
  const imageio::Image detail = testimages::generate(testimages::Pattern::Edges, W, H, 3, 8);
  wa::CombineSettings s;
  s.params = params(L);
  const wa::Planes cpu = wa::combine_planes(base, detail, s, cpu_engine());

  // Independently: Y's detail bands take the larger-magnitude coefficient, Y's LL and all of Cb and
  // Cr are the base's (so the detail's lowest band is removed).
  const wa::Planes a = wa::to_planes(base, wa::ColourSpace::YCbCr);
  const wa::Planes b = wa::to_planes(detail, wa::ColourSpace::YCbCr);
  dwt_cpu::CpuBackend backend(2);
  std::vector<float> ya = a.planes[0], yb = b.planes[0];
  backend.forward(dwt::make_span(ya.data(), W, H), s.params);
  backend.forward(dwt::make_span(yb.data(), W, H), s.params);
  const auto levels = dwt::decomposition(W, H, {}, L);
  const dwt::LayoutRect ll = dwt::band_rect(levels, L, dwt::Orientation::LL);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (x < ll.width && y < ll.height) continue;
      float& va = ya[static_cast<std::size_t>(y * W + x)];
      const float vb = yb[static_cast<std::size_t>(y * W + x)];
      if (std::abs(vb) > std::abs(va)) va = vb;
    }
  backend.inverse(dwt::make_span(ya.data(), W, H), s.params);
  EXPECT_LT(max_difference(cpu.planes[0], ya), 1e-4f * kRange);
  EXPECT_LT(max_difference(cpu.planes[1], a.planes[1]), 1e-3f);
  EXPECT_LT(max_difference(cpu.planes[2], a.planes[2]), 1e-3f);

  REQUIRE_GPU(gpu);
  const wa::Planes on_gpu = wa::combine_planes(base, detail, s, *gpu);
  // "max" is a choice, not a continuous function: where |a| and |b| are equal to within the two
  // backends' coefficient difference (about 1e-6 of the range) they may choose differently, and a
  // flipped choice moves the output by up to |a - b|. So Y must agree within 1e-4 of the range
  // everywhere but at such near-ties (at most 1% of the samples), and within 1e-3 there.
  std::size_t over = 0;
  for (std::size_t i = 0; i < cpu.planes[0].size(); ++i)
    over += std::abs(on_gpu.planes[0][i] - cpu.planes[0][i]) > 1e-4f * kRange;
  EXPECT_LE(over, cpu.planes[0].size() / 100);
  EXPECT_LT(max_difference(on_gpu.planes[0], cpu.planes[0]), 1e-3f * kRange);
  std::printf("Y samples beyond 1e-4 of the range from the CPU's: %zu of %zu\n", over, cpu.planes[0].size());
  for (std::size_t c = 1; c < 3; ++c)
    EXPECT_LT(max_difference(on_gpu.planes[c], cpu.planes[c]), 1e-4f * kRange) << "channel " << c;
}

TEST(Combine, SumAndDetailRulesOnTheGpuEqualCpu) {
  REQUIRE_GPU(gpu);
  const imageio::Image base = photo_like(64, 48, 1);
  const imageio::Image detail = testimages::generate(testimages::Pattern::ZonePlate, 40, 40, 1, 8);
  wa::CombineSettings s;
  s.params = params(2);
  s.fit = wa::Fit::Tile;
  s.bands = {wa::parse_rule_spec("1:*=sum", {{"Y"}}, 2), wa::parse_rule_spec("2:HH=detail", {{"Y"}}, 2)};
  const wa::Planes cpu = wa::combine_planes(base, detail, s, cpu_engine());
  const wa::Planes on_gpu = wa::combine_planes(base, detail, s, *gpu);
  EXPECT_LT(max_difference(on_gpu.planes[0], cpu.planes[0]), 1e-4f * kRange);
}

TEST(Combine, FitsADetailImageOfAnotherSizeByResizingOrTiling) {
  const imageio::Image base = photo_like(50, 30);
  const imageio::Image grey = testimages::generate(testimages::Pattern::GradientH, 20, 10, 1, 16);
  const imageio::Image tiled = wa::fit_detail(grey, base, wa::Fit::Tile);
  ASSERT_EQ(tiled.width, 50);
  ASSERT_EQ(tiled.channels, 3);
  EXPECT_FLOAT_EQ(tiled.at(23, 12, 1), grey.at(3, 2, 0) * 255.0f / 65535.0f);
  const imageio::Image resized = wa::fit_detail(grey, base, wa::Fit::Resize);
  EXPECT_LE(resized.at(0, 0, 0), resized.at(49, 0, 0));  // the ramp survives resizing
}

// ---- decouple -----------------------------------------------------------------------------------

TEST(Decouple, IlluminanceHasNoEnergyInTheRemovedBands) {
  const int W = 128, H = 96, L = 4;
  const imageio::Image image = photo_like(W, H, 1);
  wa::DecoupleSettings s;
  s.params = params(L);
  const wa::Decoupled d = wa::decouple_planes(image, s, cpu_engine());
  std::vector<float> coefficients = d.illuminance.planes[0];
  dwt_cpu::CpuBackend(2).forward(dwt::make_span(coefficients.data(), W, H), s.params);
  const dwt::LayoutRect ll = dwt::band_rect(dwt::decomposition(W, H, {}, L), L, dwt::Orientation::LL);
  double detail = 0, total = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double v = coefficients[static_cast<std::size_t>(y * W + x)];
      total += v * v;
      if (x >= ll.width || y >= ll.height) detail += v * v;
    }
  EXPECT_LT(detail / total, 1e-10) << "energy outside LL: " << detail << " of " << total;
}

// Texture T (fine, noise-like, mean about 150) under a smooth illumination S (0.3 to 1.0 across the
// image): the input is T * S. Measure: the RMS difference between the image and T, each divided by
// its own mean (so a uniform brightness change costs nothing). The decal must be far closer to T.
TEST(Decouple, DecalRecoversATextureUnderSmoothIlluminationOnBothBackends) {
  const int W = 128, H = 128;
  const imageio::Image noise = testimages::generate(testimages::Pattern::Noise, W, H, 1, 8, false, 7);
  imageio::Image texture = noise, lit = noise;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float t = 100.0f + 100.0f * noise.at(x, y, 0) / 255.0f;
      const float fx = static_cast<float>(x) / (W - 1), fy = static_cast<float>(y) / (H - 1);
      const float light = 0.3f + 0.7f * (0.5f * fx + 0.5f * (0.5f + 0.5f * std::sin(3.0f * fy)));
      texture.at(x, y, 0) = t;
      lit.at(x, y, 0) = t * light;
    }
  auto error_against_texture = [&](const std::vector<float>& v) {
    double mv = 0, mt = 0;
    for (std::size_t i = 0; i < v.size(); ++i) mv += v[i], mt += texture.pixels[i];
    mv /= static_cast<double>(v.size());
    mt /= static_cast<double>(v.size());
    double e = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double d = v[i] / mv - texture.pixels[i] / mt;
      e += d * d;
    }
    return std::sqrt(e / static_cast<double>(v.size()));
  };
  wa::DecoupleSettings s;
  s.params = params(4);
  const wa::Decoupled cpu = wa::decouple_planes(lit, s, cpu_engine());
  const double before = error_against_texture(lit.pixels);
  const double after = error_against_texture(cpu.decal.planes[0]);
  std::printf("relative RMS error against the texture: input %.4f, decal %.4f\n", before, after);
  EXPECT_LT(after, 0.5 * before);
  REQUIRE_GPU(gpu);
  const wa::Decoupled on_gpu = wa::decouple_planes(lit, s, *gpu);
  EXPECT_LT(max_difference(on_gpu.illuminance.planes[0], cpu.illuminance.planes[0]), 1e-4f * kRange);
  EXPECT_LT(max_difference(on_gpu.decal.planes[0], cpu.decal.planes[0]), 1e-3f * kRange);
}

// ---- deformation ----------------------------------------------------------------------------------

const wa::ControlNet& small_head() {
  static const wa::ControlNet net = wa::head_control_net(24, 32);
  return net;
}

float max_point_difference(const wa::ControlNet& a, const wa::ControlNet& b) {
  float worst = 0;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) worst = std::max(worst, std::abs(a.points[i][k] - b.points[i][k]));
  return worst;
}

TEST(Deform, AllFactorsOneReturnsTheControlNet) {
  const wa::ControlNet& net = small_head();
  ASSERT_GT(net.rows, 16);
  const wa::ControlNet same = wa::deform_net(net, params(3), {}, cpu_engine());
  EXPECT_LT(max_point_difference(same, net), 1e-6f);  // metres, on a head 0.28 m tall
  REQUIRE_GPU(gpu);
  EXPECT_LT(max_point_difference(wa::deform_net(net, params(3), {}, *gpu), net), 1e-6f);
}

TEST(Deform, ScalingOnlyTheLowestBandScalesTheCoarseExtent) {
  const wa::ControlNet& net = small_head();
  const auto axes = wa::axis_names();
  const std::vector<wa::ScaleSpec> doubled = {wa::parse_scale_spec("LL=2", axes, 3)};
  const std::vector<wa::ScaleSpec> coarse_only = {wa::parse_scale_spec("*=0", axes, 3),
                                                  wa::parse_scale_spec("LL=1", axes, 3)};
  const wa::ControlNet big = wa::deform_net(net, params(3), doubled, cpu_engine());
  const wa::ControlNet coarse = wa::deform_net(net, params(3), coarse_only, cpu_engine());
  // Linearity: the result is the net plus once more its coarse part.
  float worst = 0;
  for (std::size_t i = 0; i < net.points.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(big.points[i][k] - (net.points[i][k] + coarse.points[i][k])));
  EXPECT_LT(worst, 1e-5f);
  // The extent along each axis about doubles (the details, not scaled, account for the rest).
  for (std::size_t k = 0; k < 3; ++k) {
    auto extent = [&](const wa::ControlNet& n) {
      float lo = 1e9f, hi = -1e9f;
      for (const auto& p : n.points) lo = std::min(lo, p[k]), hi = std::max(hi, p[k]);
      return hi - lo;
    };
    const float ratio = extent(big) / extent(net);
    EXPECT_GT(ratio, 1.7f) << "axis " << k;
    EXPECT_LT(ratio, 2.3f) << "axis " << k;
  }
  REQUIRE_GPU(gpu);
  EXPECT_LT(max_point_difference(wa::deform_net(net, params(3), doubled, *gpu), big), 1e-4f * 0.3f);
}

TEST(Deform, TheSurfaceIsAValidClosedMeshAndNetsRoundTripThroughFiles) {
  const auto axes = wa::axis_names();
  const std::vector<wa::ScaleSpec> design = {wa::parse_scale_spec("2:*=1.8", axes, 3),
                                             wa::parse_scale_spec("Z:1:*=0", axes, 3)};
  const wa::ControlNet deformed = wa::deform_net(small_head(), params(3), design, cpu_engine());
  for (int subdivisions : {1, 3}) {
    const wa::SurfaceMesh mesh = wa::tessellate(deformed, subdivisions);
    EXPECT_EQ(wa::mesh_problem(mesh), "");
    // Closed: every edge is shared by exactly two triangles, in opposite directions.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
      for (int e = 0; e < 3; ++e)
        ++edges[{mesh.indices[t + static_cast<std::size_t>(e)],
                 mesh.indices[t + static_cast<std::size_t>((e + 1) % 3)]}];
    for (const auto& [edge, count] : edges) {
      ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
      ASSERT_EQ(edges.count({edge.second, edge.first}), 1u)
          << "edge " << edge.first << "-" << edge.second << " is open";
    }
  }
  test_support::ScratchDir dir("wavelet_apps");
  for (const char* name : {"net.net", "net.ply"}) {
    const auto path = dir / name;
    if (std::string(name).ends_with(".ply"))
      wa::write_control_net_ply(path, deformed);
    else
      wa::write_control_net_text(path, deformed);
    const wa::ControlNet back = wa::read_control_net(path);
    EXPECT_EQ(back.rows, deformed.rows);
    EXPECT_EQ(back.columns, deformed.columns);
    EXPECT_TRUE(back.wrap && back.capped);
    EXPECT_EQ(max_point_difference(back, deformed), 0.0f) << name;
  }
}

TEST(Deform, RejectsMalformedNetsAndTooManyLevels) {
  test_support::ScratchDir dir("wavelet_apps");
  const auto path = dir / "bad.net";
  for (const char* text : {"controlnet 2 2\n0 0 0\n1 0 0\n0 1 0\n", "controlnet 1 2\n0 0 x\n1 0 0\n", "grid 2 2\n",
                           "controlnet 2 2 twisted\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"}) {
    std::ofstream(path) << text;
    EXPECT_THROW(wa::read_control_net(path), wa::AppError) << text;
  }
  std::ofstream(path) << "controlnet 2 2\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n";
  const wa::ControlNet net = wa::read_control_net(path);
  EXPECT_THROW(wa::deform_net(net, params(4), {}, cpu_engine()), wa::AppError);
}

}  // namespace
