// The CPU lifting backend against the independent float64 reference, exact reversibility of the
// 5/3, reconstruction of the float kernels, and the request validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "dwt/error.h"
#include "dwt/params.h"
#include "dwt_cpu/cpu_backend.h"
#include "dwt_reference.h"
#include "dwt_test_matrix.h"

namespace {

using testmatrix::Shape;

dwt_cpu::CpuBackend& backend() {
  static dwt_cpu::CpuBackend cpu(2);
  return cpu;
}

std::vector<int> level_choices(Shape s, dwt::Origin o) {
  const int most = dwt::max_levels(s.w, s.h, o);
  std::vector<int> out = {most};
  if (most > 1 && std::max(s.w, s.h) < 1000) out.push_back(1);
  return out;
}

const dwt::KernelId kFloatKernels[] = {dwt::KernelId::Irreversible97, dwt::KernelId::Float53, dwt::KernelId::Haar};
const dwt::Boundary kBoundaries[] = {dwt::Boundary::Symmetric, dwt::Boundary::Periodic, dwt::Boundary::Zero};

TEST(DwtCpu, FloatKernelsMatchFloat64ConvolutionReference) {
  int configurations = 0;
  for (dwt::KernelId kid : kFloatKernels)
    for (dwt::Boundary b : kBoundaries)
      for (Shape s : testmatrix::shapes())
        for (dwt::Origin o : testmatrix::origins())
          for (int levels : level_choices(s, o)) {
            const auto input = testmatrix::samples(s.w, s.h, static_cast<std::uint32_t>(s.w * 31 + s.h));
            std::vector<float> plane = input;
            const dwt::DwtParams p{kid, b, levels, o};
            backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);

            ref::Plane r{s.w, s.h, std::vector<double>(input.begin(), input.end())};
            ref::transform(r, o.x, o.y, levels, testmatrix::to_ref(kid), testmatrix::to_ref(b), false);
            double worst = 0;
            for (std::size_t i = 0; i < plane.size(); ++i) worst = std::max(worst, std::abs(plane[i] - r.v[i]));
            // Float32 lifting vs float64 convolution: rounding only. A wrong tap, parity or
            // extension shows up as errors of whole units.
            ASSERT_LE(worst, 2e-5 * 255 * (levels + 1))
                << testmatrix::describe(dwt::get_kernel(kid).name.data(), b, s, o, levels);

            // Inverse against the reference synthesis of the same coefficients.
            std::vector<double> coeffs = r.v;
            ref::transform(r, o.x, o.y, levels, testmatrix::to_ref(kid), testmatrix::to_ref(b), true);
            std::vector<float> back(coeffs.begin(), coeffs.end());
            backend().inverse(dwt::make_span(back.data(), s.w, s.h), p);
            worst = 0;
            for (std::size_t i = 0; i < back.size(); ++i) worst = std::max(worst, std::abs(back[i] - r.v[i]));
            ASSERT_LE(worst, 2e-5 * 255 * (levels + 1))
                << "inverse, " << testmatrix::describe(dwt::get_kernel(kid).name.data(), b, s, o, levels);
            ++configurations;
          }
  RecordProperty("configurations", configurations);
}

TEST(DwtCpu, FloatKernelsReconstructWhereTheFilterBankIsPerfect) {
  for (dwt::KernelId kid : kFloatKernels)
    for (dwt::Boundary b : kBoundaries)
      for (Shape s : testmatrix::shapes())
        for (dwt::Origin o : testmatrix::origins())
          for (int levels : level_choices(s, o)) {
            if (!testmatrix::perfect_reconstruction(kid, b, s, o, levels)) continue;
            const auto input = testmatrix::samples(s.w, s.h, 7u + static_cast<std::uint32_t>(s.w));
            std::vector<float> plane = input;
            const dwt::DwtParams p{kid, b, levels, o};
            backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);
            backend().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
            double worst = 0;
            for (std::size_t i = 0; i < plane.size(); ++i)
              worst = std::max(worst, double(std::abs(plane[i] - input[i])));
            ASSERT_LE(worst, 1e-4 * 255) << testmatrix::describe(dwt::get_kernel(kid).name.data(), b, s, o, levels);
          }
}

std::vector<long> rev53_reference(const std::vector<long>& v, Shape s, dwt::Origin o, int levels) {
  return ref::rev53_analyse_2d(v, s.w, s.h, o.x, o.y, levels);
}

TEST(DwtCpu, Reversible53IsExactAgainstT800AndCloseToFloatReference) {
  for (Shape s : testmatrix::shapes())
    for (dwt::Origin o : testmatrix::origins())
      for (int levels : level_choices(s, o)) {
        const auto input = testmatrix::samples(s.w, s.h, 99u + static_cast<std::uint32_t>(s.h));
        std::vector<std::int32_t> plane(input.begin(), input.end());
        const dwt::DwtParams p{dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, levels, o};
        backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);
        const std::string what = testmatrix::describe("53", p.boundary, s, o, levels);

        const auto exact = rev53_reference(std::vector<long>(input.begin(), input.end()), s, o, levels);
        for (std::size_t i = 0; i < plane.size(); ++i) ASSERT_EQ(plane[i], exact[i]) << what << " at " << i;

        // The integer transform is the linear 5/3 plus bounded rounding.
        ref::Plane r{s.w, s.h, std::vector<double>(input.begin(), input.end())};
        ref::transform(r, o.x, o.y, levels, ref::Filter::F53, ref::Ext::Sym, false);
        for (std::size_t i = 0; i < plane.size(); ++i) ASSERT_NEAR(plane[i], r.v[i], 1.5 * (levels + 1)) << what;

        backend().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
        for (std::size_t i = 0; i < plane.size(); ++i) ASSERT_EQ(plane[i], static_cast<std::int32_t>(input[i])) << what;
      }
}

TEST(DwtCpu, Reversible53RoundTripsSixteenBitSignedData) {
  const Shape s{257, 129};
  std::mt19937 rng(5);
  std::vector<std::int32_t> input(static_cast<std::size_t>(s.w * s.h));
  for (auto& v : input) v = static_cast<std::int32_t>(rng() % 65536) - 32768;
  for (dwt::Origin o : testmatrix::origins()) {
    auto plane = input;
    const dwt::DwtParams p{dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, dwt::max_levels(s.w, s.h, o), o};
    backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);
    backend().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
    ASSERT_EQ(plane, input);
  }
}

// Samples of up to 38 bits (T.800's most) on int64 planes: the 5/3 against the exact T.800 model
// (long is 64 bits here) on data an int32 plane would overflow, and back exactly.
TEST(DwtCpu, Reversible53OnInt64PlanesIsExactForThirtyEightBitSamples) {
  static_assert(sizeof(long) == 8);
  std::mt19937_64 rng(38);
  for (Shape s : {Shape{1, 1}, Shape{1, 9}, Shape{17, 1}, Shape{33, 20}, Shape{130, 67}})
    for (dwt::Origin o : testmatrix::origins()) {
      std::vector<std::int64_t> input(static_cast<std::size_t>(s.w * s.h));
      for (auto& v : input) v = static_cast<std::int64_t>(rng() >> 26) - (std::int64_t{1} << 37);  // signed 38 bits
      const int levels = dwt::max_levels(s.w, s.h, o);
      auto plane = input;
      const dwt::DwtParams p{dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, levels, o};
      backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);
      const auto exact = rev53_reference(std::vector<long>(input.begin(), input.end()), s, o, levels);
      const std::string what = testmatrix::describe("53 int64", p.boundary, s, o, levels);
      for (std::size_t i = 0; i < plane.size(); ++i) ASSERT_EQ(plane[i], exact[i]) << what << " at " << i;
      backend().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
      ASSERT_EQ(plane, input) << what;
    }
}

// The float kernels on double planes: the float64 reference to rounding, and 38-bit samples
// reconstructed to well under half a unit, which float planes (24-bit mantissas) cannot do.
TEST(DwtCpu, FloatKernelsOnDoublePlanesKeepThirtyEightBitSamples) {
  std::mt19937_64 rng(97);
  for (Shape s : {Shape{1, 1}, Shape{2, 7}, Shape{33, 20}, Shape{130, 67}})
    for (dwt::Origin o : testmatrix::origins()) {
      std::vector<double> input(static_cast<std::size_t>(s.w * s.h));
      for (auto& v : input) v = static_cast<double>(static_cast<std::int64_t>(rng() >> 26) - (std::int64_t{1} << 37));
      const int levels = dwt::max_levels(s.w, s.h, o);
      const dwt::DwtParams p{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, levels, o};
      const std::string what = testmatrix::describe("97 double", p.boundary, s, o, levels);
      auto plane = input;
      backend().forward(dwt::make_span(plane.data(), s.w, s.h), p);
      ref::Plane r{s.w, s.h, input};
      ref::transform(r, o.x, o.y, levels, ref::Filter::F97, ref::Ext::Sym, false);
      for (std::size_t i = 0; i < plane.size(); ++i)
        ASSERT_NEAR(plane[i], r.v[i], 1e-9 * std::ldexp(1.0, 38) * (levels + 1)) << what << " at " << i;
      backend().inverse(dwt::make_span(plane.data(), s.w, s.h), p);
      for (std::size_t i = 0; i < plane.size(); ++i) ASSERT_NEAR(plane[i], input[i], 0.01) << what << " at " << i;
    }
}

TEST(DwtCpu, StridedPlanesOnlyTouchTheirOwnSamples) {
  const int w = 37, h = 23, stride = 50;
  std::vector<float> buffer(static_cast<std::size_t>(stride * h), -7.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      buffer[static_cast<std::size_t>(y * stride + x)] = static_cast<float>((x * 13 + y * 7) % 41);
  auto copy = buffer;
  dwt::PlaneSpan<float> span{buffer.data(), w, h, stride};
  const dwt::DwtParams p{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 3, {1, 0}};
  backend().forward(span, p);
  for (int y = 0; y < h; ++y)
    for (int x = w; x < stride; ++x) ASSERT_EQ(buffer[static_cast<std::size_t>(y * stride + x)], -7.0f);
  backend().inverse(span, p);
  for (std::size_t i = 0; i < buffer.size(); ++i) ASSERT_NEAR(buffer[i], copy[i], 1e-3);
}

TEST(DwtCpu, ThreadCountDoesNotChangeResults) {
  dwt_cpu::CpuBackend one(1), three(3);
  const Shape s{300, 211};
  const auto input = testmatrix::samples(s.w, s.h, 3);
  auto a = input, b = input;
  const dwt::DwtParams p{dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 5, {1, 1}};
  one.forward(dwt::make_span(a.data(), s.w, s.h), p);
  three.forward(dwt::make_span(b.data(), s.w, s.h), p);
  ASSERT_EQ(a, b);
}

TEST(DwtCpu, RejectsImpossibleRequests) {
  std::vector<float> f(64);
  std::vector<std::int32_t> i(64);
  auto& cpu = backend();
  EXPECT_THROW(
      cpu.forward(dwt::make_span(f.data(), 8, 8), {dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 4, {}}),
      dwt::DwtError);
  EXPECT_THROW(cpu.forward(dwt::make_span(f.data(), 0, 8), {}), dwt::DwtError);
  EXPECT_THROW(
      cpu.forward(dwt::make_span(f.data(), 8, 8), {dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, 1, {}}),
      dwt::DwtError);
  EXPECT_THROW(
      cpu.forward(dwt::make_span(i.data(), 8, 8), {dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 1, {}}),
      dwt::DwtError);
  EXPECT_THROW(cpu.forward(dwt::make_span(f.data(), 8, 8),
                           {dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 1, {-1, 0}}),
               dwt::DwtError);
  try {
    cpu.forward(dwt::make_span(f.data(), 8, 8), {dwt::KernelId::Irreversible97, dwt::Boundary::Symmetric, 9, {}});
    FAIL();
  } catch (const dwt::DwtError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(dwt::parse_kernel("79"), dwt::DwtError);
  EXPECT_THROW(dwt::parse_boundary("mirror"), dwt::DwtError);
}

}  // namespace

namespace {

// A codec's edge tile may be smaller than its level count needs; the extra levels must still be
// well defined (lone samples pass or double) and invertible.
TEST(DwtCpu, ExtraLevelsOnTinyPlanesWhenTheCodecAsksForThem) {
  for (Shape s : {Shape{1, 1}, Shape{1, 13}, Shape{2, 3}, Shape{5, 1}})
    for (dwt::Origin o : testmatrix::origins()) {
      const auto input = testmatrix::samples(s.w, s.h, 1);
      std::vector<std::int32_t> ints(input.begin(), input.end());
      dwt::DwtParams p{dwt::KernelId::Reversible53, dwt::Boundary::Symmetric, 7, o};
      EXPECT_THROW(backend().forward(dwt::make_span(ints.data(), s.w, s.h), p), dwt::DwtError);
      p.levels_may_exceed_size = true;
      backend().forward(dwt::make_span(ints.data(), s.w, s.h), p);
      const auto exact = rev53_reference(std::vector<long>(input.begin(), input.end()), s, o, 7);
      for (std::size_t i = 0; i < ints.size(); ++i) ASSERT_EQ(ints[i], exact[i]);
      backend().inverse(dwt::make_span(ints.data(), s.w, s.h), p);
      for (std::size_t i = 0; i < ints.size(); ++i) ASSERT_EQ(ints[i], static_cast<std::int32_t>(input[i]));
    }
}

}  // namespace
