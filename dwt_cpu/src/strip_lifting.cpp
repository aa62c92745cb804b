#include "strip_lifting.h"

#include <algorithm>
#include <iterator>
#include <type_traits>

#include "dwt/error.h"
#include "lifting_simd.h"

namespace dwt_cpu {
namespace {

// The first interior line of class `target_class` (line 0 has no upper neighbour).
template <class T>
int first_target_line(const Strip<T>& s, int target_class) {
  return s.class_of(1) == target_class ? 1 : 2;
}

// Every line of each class scaled by its class' gain (or undone).
void apply_gains(const dwt::Kernel& k, const Strip<float>& s, bool inverse) {
  for (int c = 0; c < 2; ++c) {
    const double g = c == 0 ? k.low_gain : k.high_gain;
    if (g != 1.0)
      simd::scale_lines(s.data, s.stride, s.lanes, s.class_of(0) == c ? 0 : 1, s.lines,
                        static_cast<float>(inverse ? 1.0 / g : g));
  }
}

void lift_step(const Strip<float>& s, int target_class, float cl, float cr) {
  const int first = first_target_line(s, target_class);
  if (cl == cr)
    simd::lift_lines_symmetric(s.data, s.stride, s.lanes, first, s.lines, cl);
  else
    simd::lift_lines_general(s.data, s.stride, s.lanes, first, s.lines, cl, cr);
}

void require_reversible(const dwt::Kernel& k) {
  if (k.id != dwt::KernelId::Reversible53) throw dwt::DwtError("integer planes need the reversible 5/3 kernel");
}

}  // namespace

void lift_forward(const dwt::Kernel& k, const Strip<float>& s) {
  for (const dwt::LiftingStep& step : k.steps)
    lift_step(s, static_cast<int>(step.target), static_cast<float>(step.left), static_cast<float>(step.right));
  apply_gains(k, s, false);
}

void lift_inverse(const dwt::Kernel& k, const Strip<float>& s) {
  apply_gains(k, s, true);
  for (auto it = k.steps.rbegin(); it != k.steps.rend(); ++it)
    lift_step(s, static_cast<int>(it->target), static_cast<float>(-it->left), static_cast<float>(-it->right));
}

void lift_forward(const dwt::Kernel& k, const Strip<std::int32_t>& s) {
  require_reversible(k);
  simd::predict53_lines(s.data, s.stride, s.lanes, first_target_line(s, 1), s.lines, false);
  simd::update53_lines(s.data, s.stride, s.lanes, first_target_line(s, 0), s.lines, false);
}

void lift_inverse(const dwt::Kernel& k, const Strip<std::int32_t>& s) {
  require_reversible(k);
  simd::update53_lines(s.data, s.stride, s.lanes, first_target_line(s, 0), s.lines, true);
  simd::predict53_lines(s.data, s.stride, s.lanes, first_target_line(s, 1), s.lines, true);
}

template <class T>
StreamingForwardLift<T>::StreamingForwardLift(const dwt::Kernel& k, const Strip<T>& s) : strip_(s) {
  if constexpr (std::is_integral_v<T>) {
    require_reversible(k);
    steps_[0] = Step{1, 0, 0, first_target_line(s, 1)};  // predict
    steps_[1] = Step{0, 0, 0, first_target_line(s, 0)};  // update
    step_count_ = 2;
  } else {
    if (k.steps.size() > std::size(steps_)) throw dwt::DwtError("a kernel of more than four lifting steps");
    for (const dwt::LiftingStep& step : k.steps) {
      const int c = static_cast<int>(step.target);
      steps_[step_count_++] = Step{c, step.left, step.right, first_target_line(s, c)};
    }
  }
}

template <class T>
void StreamingForwardLift<T>::apply(const Step& step, int end) const {
  const Strip<T>& s = strip_;
  if constexpr (std::is_integral_v<T>) {
    if (step.target_class == 1)
      simd::predict53_lines(s.data, s.stride, s.lanes, step.next, end, false);
    else
      simd::update53_lines(s.data, s.stride, s.lanes, step.next, end, false);
  } else {
    const auto cl = static_cast<float>(step.left), cr = static_cast<float>(step.right);
    if (cl == cr)
      simd::lift_lines_symmetric(s.data, s.stride, s.lanes, step.next, end, cl);
    else
      simd::lift_lines_general(s.data, s.stride, s.lanes, step.next, end, cl, cr);
  }
}

template <class T>
int StreamingForwardLift<T>::advance(int available) {
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

template class StreamingForwardLift<float>;
template class StreamingForwardLift<std::int32_t>;

}  // namespace dwt_cpu
