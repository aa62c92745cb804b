#include "strip_lifting.h"

#include <algorithm>
#include <iterator>
#include <type_traits>

#include "dwt/error.h"
#include "kernel_checks.h"
#include "lifting_simd.h"
#include "lifting_wide.h"

namespace dwt_cpu {
namespace {

// The first interior line of class `target_class` (line 0 has no upper neighbour).
template <class T>
int first_target_line(const Strip<T>& s, int target_class) {
  return s.class_of(1) == target_class ? 1 : 2;
}

}  // namespace

template <class T>
StreamingLift<T>::StreamingLift(const dwt::Kernel& k, const Strip<T>& s, bool inverse) : strip_(s), inverse_(inverse) {
  auto add = [&](int target_class, double left, double right) {
    steps_[step_count_++] = Step{target_class, left, right, first_target_line(s, target_class)};
  };
  if constexpr (std::is_integral_v<T>) {
    require_reversible(k);
    if (inverse) {
      add(0, 0, 0);  // update undone
      add(1, 0, 0);  // predict undone
    } else {
      add(1, 0, 0);  // predict
      add(0, 0, 0);  // update
    }
  } else {
    if (k.steps.size() > std::size(steps_)) throw dwt::DwtError("a kernel of more than four lifting steps");
    if (inverse)
      for (auto it = k.steps.rbegin(); it != k.steps.rend(); ++it)
        add(static_cast<int>(it->target), -it->left, -it->right);
    else
      for (const dwt::LiftingStep& step : k.steps) add(static_cast<int>(step.target), step.left, step.right);
  }
}

template <class T>
void StreamingLift<T>::apply(const Step& step, int end) const {
  const Strip<T>& s = strip_;
  if constexpr (std::is_integral_v<T>) {
    if (step.target_class == 1)
      simd::predict53_lines(s.data, s.stride, s.lanes, step.next, end, inverse_);
    else
      simd::update53_lines(s.data, s.stride, s.lanes, step.next, end, inverse_);
  } else {
    const auto cl = static_cast<T>(step.left), cr = static_cast<T>(step.right);
    if (cl == cr)
      simd::lift_lines_symmetric(s.data, s.stride, s.lanes, step.next, end, cl);
    else
      simd::lift_lines_general(s.data, s.stride, s.lanes, step.next, end, cl, cr);
  }
}

template <class T>
int StreamingLift<T>::advance(int available) {
  // Lines below `ready` have had every step so far: a step's target b needs b - 1 and b + 1 there.
  int ready = std::min(available, strip_.lines);
  for (int i = 0; i < step_count_; ++i) {
    Step& step = steps_[i];
    if (step.next + 1 < ready) {
      apply(step, ready);  // targets next, next + 2, ... while target + 1 < ready
      step.next += 2 * ((ready - step.next) / 2);
    }
    ready = std::min(ready, step.next);
  }
  return available >= strip_.lines ? strip_.lines : ready;
}

template class StreamingLift<float>;
template class StreamingLift<std::int32_t>;
template class StreamingLift<double>;
template class StreamingLift<std::int64_t>;

}  // namespace dwt_cpu
