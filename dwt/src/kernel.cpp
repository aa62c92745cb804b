#include "dwt/kernel.h"

#include "dwt/error.h"

#include <cmath>
#include <string>

namespace dwt {
namespace {

// Irreversible 9/7 lifting parameters, T.800 Table F.4.
constexpr double kAlpha = -1.586134342059924;
constexpr double kBeta = -0.052980118572961;
constexpr double kGamma = 0.882911075530934;
constexpr double kDelta = 0.443506852043971;
constexpr double kK = 1.230174104914001;

int class_at(std::size_t i, int parity0) { return static_cast<int>((i + static_cast<std::size_t>(parity0)) & 1u); }

// Impulse responses of the lifting network give the convolution taps, so the GPU convolves with
// exactly the filter bank the CPU lifts with.
void derive_taps(Kernel& k) {
  constexpr int kLen = 64;
  constexpr int kCentre = 32;
  const int R = Kernel::kMaxRadius;
  for (int c = 0; c < 2; ++c) {
    // Analysis: the output at e (class c) as a function of an impulse at e + t.
    for (int t = -R; t <= R; ++t) {
      std::vector<double> x(kLen, 0.0);
      x[kCentre + t] = 1.0;
      lift_forward_f64(k, x, c);  // parity chosen so that index kCentre (even) has class c
      k.analysis[c][t + R] = x[kCentre];
    }
    // Synthesis: the sample at m (class c) as a function of a unit coefficient at m + t.
    for (int t = -R; t <= R; ++t) {
      std::vector<double> y(kLen, 0.0);
      y[kCentre + t] = 1.0;
      lift_inverse_f64(k, y, c);
      k.synthesis[c][t + R] = y[kCentre];
    }
  }
  auto radius = [&](const std::array<Kernel::Taps, 2>& bank) {
    int r = 0;
    for (const auto& taps : bank)
      for (int t = -R; t <= R; ++t)
        if (std::abs(taps[t + R]) > 1e-15) r = std::max(r, std::abs(t));
    return r;
  };
  k.analysis_radius = radius(k.analysis);
  k.synthesis_radius = radius(k.synthesis);
}

Kernel make(KernelId id, std::string_view name, std::string_view description, bool reversible,
            std::vector<LiftingStep> steps, double low_gain, double high_gain) {
  Kernel k{id, name, description, reversible, std::move(steps), low_gain, high_gain};
  derive_taps(k);
  return k;
}

const std::array<Kernel, 4>& all_kernels() {
  static const std::array<Kernel, 4> kernels = {
      make(KernelId::Irreversible97, "97", "JPEG 2000 irreversible 9/7", false,
           {{SampleClass::High, kAlpha, kAlpha},
            {SampleClass::Low, kBeta, kBeta},
            {SampleClass::High, kGamma, kGamma},
            {SampleClass::Low, kDelta, kDelta}},
           1.0 / kK, kK),
      // The reversible kernel's rounding lives in the backends; these are its unrounded steps.
      make(KernelId::Reversible53, "53", "JPEG 2000 reversible 5/3 (integer)", true,
           {{SampleClass::High, -0.5, -0.5}, {SampleClass::Low, 0.25, 0.25}}, 1.0, 1.0),
      make(KernelId::Float53, "53f", "5/3 in floating point", false,
           {{SampleClass::High, -0.5, -0.5}, {SampleClass::Low, 0.25, 0.25}}, 1.0, 1.0),
      // Haar with the same gains: low = (x0 + x1) / 2, high = x1 - x0.
      make(KernelId::Haar, "haar", "Haar", false, {{SampleClass::High, -1.0, 0.0}, {SampleClass::Low, 0.0, 0.5}}, 1.0,
           1.0),
  };
  return kernels;
}

}  // namespace

void lift_forward_f64(const Kernel& k, std::vector<double>& x, int parity0) {
  const std::size_t n = x.size();
  for (const LiftingStep& s : k.steps)
    for (std::size_t i = 1; i + 1 < n; ++i)
      if (class_at(i, parity0) == static_cast<int>(s.target)) x[i] += s.left * x[i - 1] + s.right * x[i + 1];
  for (std::size_t i = 0; i < n; ++i) x[i] *= class_at(i, parity0) == 0 ? k.low_gain : k.high_gain;
}

void lift_inverse_f64(const Kernel& k, std::vector<double>& y, int parity0) {
  const std::size_t n = y.size();
  for (std::size_t i = 0; i < n; ++i) y[i] /= class_at(i, parity0) == 0 ? k.low_gain : k.high_gain;
  for (auto it = k.steps.rbegin(); it != k.steps.rend(); ++it)
    for (std::size_t i = 1; i + 1 < n; ++i)
      if (class_at(i, parity0) == static_cast<int>(it->target)) y[i] -= it->left * y[i - 1] + it->right * y[i + 1];
}

const Kernel& get_kernel(KernelId id) {
  for (const Kernel& k : all_kernels())
    if (k.id == id) return k;
  throw DwtError("unknown kernel id");
}

std::string_view kernel_names() { return "97|53|53f|haar"; }

KernelId parse_kernel(std::string_view name) {
  for (const Kernel& k : all_kernels())
    if (k.name == name) return k.id;
  throw DwtError("unknown kernel '" + std::string(name) + "' (expected one of " + std::string(kernel_names()) + ")");
}

}  // namespace dwt
