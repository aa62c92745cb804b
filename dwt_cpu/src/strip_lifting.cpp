#include "strip_lifting.h"

#include "dwt/error.h"
#include "lifting_simd.h"

namespace dwt_cpu {
namespace {

// Calls op(target, left, right) for every interior line of class `target_class`.
template <class T, class Op>
void for_each_target_line(const Strip<T>& s, int target_class, Op op) {
  const int first = s.class_of(1) == target_class ? 1 : 2;
  for (int b = first; b + 1 < s.lines; b += 2) op(s.line(b), s.line(b - 1), s.line(b + 1));
}

void apply_gains(const dwt::Kernel& k, const Strip<float>& s, bool inverse) {
  for (int b = 0; b < s.lines; ++b) {
    const double g = s.class_of(b) == 0 ? k.low_gain : k.high_gain;
    if (g != 1.0) simd::scale(s.line(b), static_cast<float>(inverse ? 1.0 / g : g), s.lanes);
  }
}

void require_reversible(const dwt::Kernel& k) {
  if (k.id != dwt::KernelId::Reversible53) throw dwt::DwtError("integer planes need the reversible 5/3 kernel");
}

}  // namespace

void lift_forward(const dwt::Kernel& k, const Strip<float>& s) {
  for (const dwt::LiftingStep& step : k.steps) {
    const auto cl = static_cast<float>(step.left), cr = static_cast<float>(step.right);
    for_each_target_line(s, static_cast<int>(step.target), [&](float* t, const float* l, const float* r) {
      if (cl == cr)
        simd::lift_symmetric(t, l, r, cl, s.lanes);
      else
        simd::lift_general(t, l, r, cl, cr, s.lanes);
    });
  }
  apply_gains(k, s, false);
}

void lift_inverse(const dwt::Kernel& k, const Strip<float>& s) {
  apply_gains(k, s, true);
  for (auto it = k.steps.rbegin(); it != k.steps.rend(); ++it) {
    const auto cl = static_cast<float>(-it->left), cr = static_cast<float>(-it->right);
    for_each_target_line(s, static_cast<int>(it->target), [&](float* t, const float* l, const float* r) {
      if (cl == cr)
        simd::lift_symmetric(t, l, r, cl, s.lanes);
      else
        simd::lift_general(t, l, r, cl, cr, s.lanes);
    });
  }
}

void lift_forward(const dwt::Kernel& k, const Strip<std::int32_t>& s) {
  require_reversible(k);
  using I = std::int32_t;
  for_each_target_line(s, 1, [&](I* t, const I* l, const I* r) { simd::predict53(t, l, r, s.lanes, false); });
  for_each_target_line(s, 0, [&](I* t, const I* l, const I* r) { simd::update53(t, l, r, s.lanes, false); });
}

void lift_inverse(const dwt::Kernel& k, const Strip<std::int32_t>& s) {
  require_reversible(k);
  using I = std::int32_t;
  for_each_target_line(s, 0, [&](I* t, const I* l, const I* r) { simd::update53(t, l, r, s.lanes, true); });
  for_each_target_line(s, 1, [&](I* t, const I* l, const I* r) { simd::predict53(t, l, r, s.lanes, true); });
}

}  // namespace dwt_cpu
