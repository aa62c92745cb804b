#pragma once
#include "dwt/boundary.h"
#include "dwt/geometry.h"
#include "dwt/kernel.h"
#include "dwt/plane.h"
#include "base/thread_pool.h"

namespace dwt_cpu {

enum class Axis { Horizontal, Vertical };

// One level's 1-D transform along one axis of the top-left region of the plane (region_width x
// region_height samples). `span` gives that axis' length and reference-grid start (for parity).
// Forward leaves low-pass samples first, then high-pass, along the axis; inverse undoes it.
struct AxisPass {
  const dwt::Kernel& kernel;
  dwt::Boundary boundary;
  Axis axis;
  dwt::AxisSpan span;
  int region_width;
  int region_height;
};

template <class T>
void run_forward(const AxisPass& pass, dwt::PlaneSpan<T> plane, base::ThreadPool& pool);
template <class T>
void run_inverse(const AxisPass& pass, dwt::PlaneSpan<T> plane, base::ThreadPool& pool);

}  // namespace dwt_cpu
