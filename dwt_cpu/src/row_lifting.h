#pragma once
#include <cstddef>
#include <cstdint>

#include "dwt/kernel.h"

namespace dwt_cpu {

// One boundary-extended signal split into its two polyphase components, each contiguous, so the
// lifting steps become element-wise operations between two arrays (no transposes). This is how the
// horizontal pass works: a row's samples are already contiguous.
//   low[j]  sits at extended position first_low + 2j,
//   high[j] sits at extended position 1 - first_low + 2j.
template <class T>
struct SplitSignal {
  T* low = nullptr;
  T* high = nullptr;
  int low_size = 0;
  int high_size = 0;
  int first_low = 0;  // 0 or 1
};

void lift_forward(const dwt::Kernel& kernel, const SplitSignal<float>& s);
// lift_forward without its gains, for a caller that applies them as it copies the result out.
void lift_forward_steps(const dwt::Kernel& kernel, const SplitSignal<float>& s);
void lift_inverse(const dwt::Kernel& kernel, const SplitSignal<float>& s);
void lift_forward(const dwt::Kernel& kernel, const SplitSignal<std::int32_t>& s);
void lift_inverse(const dwt::Kernel& kernel, const SplitSignal<std::int32_t>& s);
// The same on 64-bit lanes (lifting_wide.h), for samples of more than 31 bits.
void lift_forward(const dwt::Kernel& kernel, const SplitSignal<double>& s);
void lift_forward_steps(const dwt::Kernel& kernel, const SplitSignal<double>& s);
void lift_inverse(const dwt::Kernel& kernel, const SplitSignal<double>& s);
void lift_forward(const dwt::Kernel& kernel, const SplitSignal<std::int64_t>& s);
void lift_inverse(const dwt::Kernel& kernel, const SplitSignal<std::int64_t>& s);

}  // namespace dwt_cpu
