#pragma once
#include <array>
#include <string_view>
#include <vector>

namespace dwt {

enum class KernelId {
  Irreversible97,  // JPEG 2000 CDF 9/7, float (T.800 Annex F, Table F.4)
  Reversible53,    // JPEG 2000 LeGall 5/3, integer to integer, exact (T.800 F.3.8.1 / F.4.8.1)
  Float53,         // the same 5/3 filter bank without rounding, for wavelet applications
  Haar,            // two-tap Haar, for wavelet applications
};

// Which polyphase component a sample belongs to. JPEG 2000 fixes it by the parity of the sample's
// coordinate on the reference grid, not by its index in the tile (T.800 Annex F): even -> low-pass.
enum class SampleClass { Low = 0, High = 1 };

inline SampleClass class_of(long long canvas_coordinate) {
  return (canvas_coordinate & 1) ? SampleClass::High : SampleClass::Low;
}

// One lifting step: every sample of class `target` gains left * (its left neighbour) +
// right * (its right neighbour). Symmetric kernels have left == right.
struct LiftingStep {
  SampleClass target;
  double left;
  double right;
};

// A kernel is data: its lifting factorisation, final gains, and the convolution taps derived from
// them (what the GPU's fragment shader convolves with). Normalisation is JPEG 2000's: the low-pass
// analysis filter has DC gain 1 and the high-pass analysis filter Nyquist gain 2.
struct Kernel {
  static constexpr int kMaxRadius = 4;
  static constexpr int kTaps = 2 * kMaxRadius + 1;
  using Taps = std::array<double, kTaps>;  // index t + kMaxRadius, t in [-kMaxRadius, kMaxRadius]

  KernelId id;
  std::string_view name;         // command-line name: 97, 53, 53f, haar
  std::string_view description;  // for --help and benchmark lines
  bool reversible;               // integer in, integer out (needs int32 planes)
  std::vector<LiftingStep> steps;
  double low_gain;   // applied to low-pass samples after the lifting steps
  double high_gain;  // applied to high-pass samples after the lifting steps

  // Analysis: output at position e of class c is sum_t analysis[c][t] * x(e + t).
  std::array<Taps, 2> analysis{};
  // Synthesis on the interleaved coefficient sequence y: x(m) = sum_t synthesis[class(m)][t] * y(m + t)
  // (the thesis' interleaved reconstruction kernels, figure 4.8).
  std::array<Taps, 2> synthesis{};
  int analysis_radius = 0;
  int synthesis_radius = 0;
};

const Kernel& get_kernel(KernelId id);
KernelId parse_kernel(std::string_view name);  // "97", "53", "53f", "haar"
std::string_view kernel_names();               // "97|53|53f|haar", for messages

// Float64 lifting over a whole buffer whose element 0 has reference-grid parity `parity0`; used to
// derive the convolution taps, and handy as a slow single-row model. Ends are left unextended, so
// only samples farther than the kernel's support from either end are meaningful.
void lift_forward_f64(const Kernel& k, std::vector<double>& x, int parity0);
void lift_inverse_f64(const Kernel& k, std::vector<double>& y, int parity0);

}  // namespace dwt
