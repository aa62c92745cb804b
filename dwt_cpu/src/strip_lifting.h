#pragma once
#include <cstddef>
#include <cstdint>

#include "dwt/kernel.h"

namespace dwt_cpu {

// A block of lines that owns nothing. Line b holds position b - pad of a boundary-extended 1-D
// signal, for `lanes` independent signals side by side. The class (low/high) of line b is
// (b + first_class) & 1. Lifting over the whole padded strip equals convolving the extended signal,
// so any boundary scheme comes out right in the interior lines.
template <class T>
struct Strip {
  T* data = nullptr;
  int lines = 0;
  std::size_t lanes = 0;
  std::size_t stride = 0;
  int first_class = 0;

  T* line(int b) const { return data + static_cast<std::size_t>(b) * stride; }
  int class_of(int b) const { return (b + first_class) & 1; }
};

// A kernel's lifting steps over a strip (analysis: the steps in order; synthesis: reversed and
// negated, on lines whose gains the caller has undone; the caller applies the analysis gains),
// applied while the strip's lines arrive top to bottom, so that each line is lifted while it is
// still in the cache rather than once per step over the whole strip. advance(available), with
// lines [0, available) filled, applies every step as far as they allow; each target line gets each
// step once, with its neighbours at the stage lifting the whole strip step by step gives them, so
// once advance(strip.lines) has run the strip is bit for bit what that gives. Lines within
// kernel.steps.size() of either end are left with meaningless values: the caller pads by at least
// that. advance returns how many leading lines no later step will change.
template <class T>
class StreamingLift {
 public:
  StreamingLift(const dwt::Kernel& kernel, const Strip<T>& strip, bool inverse);
  int advance(int available);

 private:
  struct Step {
    int target_class;
    double left, right;  // the coefficients, negated for the inverse (float strips)
    int next;            // the next target line to lift
  };
  Strip<T> strip_;
  bool inverse_;
  Step steps_[4];
  int step_count_ = 0;
  void apply(const Step& step, int end) const;
};

}  // namespace dwt_cpu
