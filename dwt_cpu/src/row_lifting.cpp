#include "row_lifting.h"
#include <algorithm>

#include "dwt/error.h"
#include "kernel_checks.h"
#include "lifting_simd.h"
#include "lifting_wide.h"

namespace dwt_cpu {
namespace {

// The run of target samples that have both neighbours inside the extended signal, and where those
// neighbours start in the other component. Positions at the very ends are skipped, as the strip
// form skips its first and last lines; padding keeps them out of the interior's reach.
struct StepRange {
  int first = 0;       // first target index
  int count = 0;       // number of targets
  int left_first = 0;  // index in the other component of the first target's left neighbour
};

template <class T>
StepRange step_range(const SplitSignal<T>& s, int target_class) {
  const int target_start = target_class == 0 ? s.first_low : 1 - s.first_low;
  const int target_size = target_class == 0 ? s.low_size : s.high_size;
  const int other_size = target_class == 0 ? s.high_size : s.low_size;
  StepRange r;
  if (target_start == 0) {  // target j at 2j: neighbours other[j-1], other[j]
    r.first = 1;
    r.left_first = 0;
    r.count = std::min(target_size, other_size) - 1;
  } else {  // target j at 2j+1: neighbours other[j], other[j+1]
    r.first = 0;
    r.left_first = 0;
    r.count = std::min(target_size, other_size - 1);
  }
  if (r.count < 0) r.count = 0;
  return r;
}

template <class T>
void for_step(const SplitSignal<T>& s, int target_class, auto op) {
  const StepRange r = step_range(s, target_class);
  if (r.count == 0) return;
  T* target = (target_class == 0 ? s.low : s.high) + r.first;
  const T* other = (target_class == 0 ? s.high : s.low) + r.left_first;
  op(target, other, other + 1, static_cast<std::size_t>(r.count));
}

// The float kernels on float or double signals.
template <class T>
void lift_real(const dwt::Kernel& k, const SplitSignal<T>& s, bool inverse, bool gains = true) {
  if (inverse) {
    simd::scale(s.low, static_cast<T>(1.0 / k.low_gain), static_cast<std::size_t>(s.low_size));
    simd::scale(s.high, static_cast<T>(1.0 / k.high_gain), static_cast<std::size_t>(s.high_size));
  }
  const int n = static_cast<int>(k.steps.size());
  for (int i = 0; i < n; ++i) {
    const dwt::LiftingStep& step = k.steps[static_cast<std::size_t>(inverse ? n - 1 - i : i)];
    const auto cl = static_cast<T>(inverse ? -step.left : step.left);
    const auto cr = static_cast<T>(inverse ? -step.right : step.right);
    for_step(s, static_cast<int>(step.target), [&](T* t, const T* l, const T* r, std::size_t count) {
      if (cl == cr)
        simd::lift_symmetric(t, l, r, cl, count);
      else
        simd::lift_general(t, l, r, cl, cr, count);
    });
  }
  if (!inverse && gains) {
    simd::scale(s.low, static_cast<T>(k.low_gain), static_cast<std::size_t>(s.low_size));
    simd::scale(s.high, static_cast<T>(k.high_gain), static_cast<std::size_t>(s.high_size));
  }
}

}  // namespace

void lift_forward(const dwt::Kernel& k, const SplitSignal<float>& s) { lift_real(k, s, false); }
void lift_forward_steps(const dwt::Kernel& k, const SplitSignal<float>& s) { lift_real(k, s, false, false); }
void lift_inverse(const dwt::Kernel& k, const SplitSignal<float>& s) { lift_real(k, s, true); }
void lift_forward(const dwt::Kernel& k, const SplitSignal<double>& s) { lift_real(k, s, false); }
void lift_forward_steps(const dwt::Kernel& k, const SplitSignal<double>& s) { lift_real(k, s, false, false); }
void lift_inverse(const dwt::Kernel& k, const SplitSignal<double>& s) { lift_real(k, s, true); }

namespace {

template <class I>
void lift_integer(const dwt::Kernel& k, const SplitSignal<I>& s, bool inverse) {
  require_reversible(k);
  auto predict = [inverse](I* t, const I* l, const I* r, std::size_t n) { simd::predict53(t, l, r, n, inverse); };
  auto update = [inverse](I* t, const I* l, const I* r, std::size_t n) { simd::update53(t, l, r, n, inverse); };
  if (inverse) {
    for_step(s, 0, update);
    for_step(s, 1, predict);
  } else {
    for_step(s, 1, predict);
    for_step(s, 0, update);
  }
}

}  // namespace

void lift_forward(const dwt::Kernel& k, const SplitSignal<std::int32_t>& s) { lift_integer(k, s, false); }
void lift_inverse(const dwt::Kernel& k, const SplitSignal<std::int32_t>& s) { lift_integer(k, s, true); }
void lift_forward(const dwt::Kernel& k, const SplitSignal<std::int64_t>& s) { lift_integer(k, s, false); }
void lift_inverse(const dwt::Kernel& k, const SplitSignal<std::int64_t>& s) { lift_integer(k, s, true); }

}  // namespace dwt_cpu
