#include "axis_pass.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "strip_lifting.h"

namespace dwt_cpu {
namespace {

// Lanes per strip. Horizontal strips gather rows side by side (a transpose into the strip), so a
// few rows fill a vector; vertical strips copy contiguous runs of columns, wide enough to stream
// whole cache lines but small enough that a tall strip stays in L2.
constexpr std::size_t kHorizontalLanes = 16;
constexpr std::size_t kVerticalLanes = 64;

struct Layout {
  int n;          // samples along the axis
  int lanes;      // independent signals (rows for horizontal, columns for vertical)
  int pad;        // extension lines on each side of the strip
  int parity;     // reference-grid parity of the first sample
  int low;        // low-pass count
  std::size_t strip_lanes;
};

Layout layout_of(const AxisPass& p) {
  const bool h = p.axis == Axis::Horizontal;
  return Layout{p.span.length,
                h ? p.region_height : p.region_width,
                static_cast<int>(p.kernel.steps.size()),
                p.span.parity(),
                p.span.low_count(),
                h ? kHorizontalLanes : kVerticalLanes};
}

// Where strip line b reads its sample from: for the forward transform an index into the signal,
// for the inverse an index into the Mallat-ordered coefficients (the thesis' "virtual upsampling
// and interleaving"); -1 reads zero.
std::vector<int> source_map(const Layout& L, dwt::Boundary boundary, bool inverse) {
  std::vector<int> map(static_cast<std::size_t>(L.n + 2 * L.pad));
  for (int b = 0; b < static_cast<int>(map.size()); ++b) {
    const auto q = static_cast<int>(dwt::extend_index(b - L.pad, L.n, boundary));
    if (!inverse || q < 0)
      map[static_cast<std::size_t>(b)] = q;
    else if (((q + L.parity) & 1) == 0)
      map[static_cast<std::size_t>(b)] = (q - L.parity) >> 1;
    else
      map[static_cast<std::size_t>(b)] = L.low + ((q - 1 + L.parity) >> 1);
  }
  return map;
}

// Destination index along the axis for signal position e after the forward transform.
int mallat_index(const Layout& L, int e) {
  return ((e + L.parity) & 1) == 0 ? (e - L.parity) >> 1 : L.low + ((e - 1 + L.parity) >> 1);
}

// A lone sample: T.800 F.3.7 / F.4.7 keep an even one and double an odd one.
template <class T>
void single_sample(const AxisPass& p, dwt::PlaneSpan<T> plane, bool inverse) {
  if (p.span.parity() == 0) return;
  auto apply = [&](T& v) {
    if constexpr (std::is_integral_v<T>)
      v = inverse ? (v >> 1) : static_cast<T>(v * 2);
    else
      v = inverse ? v * T(0.5) : v * T(2);
  };
  if (p.axis == Axis::Horizontal)
    for (int y = 0; y < p.region_height; ++y) apply(plane.at(0, y));
  else
    for (int x = 0; x < p.region_width; ++x) apply(plane.at(x, 0));
}

template <class T>
void run(const AxisPass& p, dwt::PlaneSpan<T> plane, ThreadPool& pool, bool inverse) {
  const Layout L = layout_of(p);
  if (L.n == 0 || L.lanes == 0) return;
  if (L.n == 1) return single_sample(p, plane, inverse);

  const std::vector<int> map = source_map(L, p.boundary, inverse);
  const int lines = L.n + 2 * L.pad;
  const std::size_t strips = (static_cast<std::size_t>(L.lanes) + L.strip_lanes - 1) / L.strip_lanes;
  // Line 0 holds position -pad; its class follows from the parity of the first sample.
  const int first_class = (L.parity - L.pad) & 1;

  pool.parallel_for(strips, [&](std::size_t s) {
    thread_local std::vector<T> scratch;
    const std::size_t W = L.strip_lanes;
    scratch.resize(static_cast<std::size_t>(lines) * W);
    const int lane0 = static_cast<int>(s * W);
    const std::size_t lanes = std::min<std::size_t>(W, static_cast<std::size_t>(L.lanes - lane0));
    Strip<T> strip{scratch.data(), lines, lanes, W, first_class};

    // Gather the (extended) signals into the strip.
    for (int b = 0; b < lines; ++b) {
      T* line = strip.line(b);
      const int src = map[static_cast<std::size_t>(b)];
      if (src < 0) {
        std::fill(line, line + lanes, T(0));
      } else if (p.axis == Axis::Vertical) {
        std::memcpy(line, plane.row(src) + lane0, lanes * sizeof(T));
      } else {
        for (std::size_t r = 0; r < lanes; ++r) line[r] = plane.row(lane0 + static_cast<int>(r))[src];
      }
    }

    if (inverse)
      lift_inverse(p.kernel, strip);
    else
      lift_forward(p.kernel, strip);

    // Scatter the interior back: deinterleaved into the Mallat order (forward) or in signal order.
    for (int e = 0; e < L.n; ++e) {
      const T* line = strip.line(e + L.pad);
      const int dst = inverse ? e : mallat_index(L, e);
      if (p.axis == Axis::Vertical) {
        std::memcpy(plane.row(dst) + lane0, line, lanes * sizeof(T));
      } else {
        for (std::size_t r = 0; r < lanes; ++r) plane.row(lane0 + static_cast<int>(r))[dst] = line[r];
      }
    }
  });
}

}  // namespace

template <class T>
void run_forward(const AxisPass& pass, dwt::PlaneSpan<T> plane, ThreadPool& pool) {
  run(pass, plane, pool, false);
}
template <class T>
void run_inverse(const AxisPass& pass, dwt::PlaneSpan<T> plane, ThreadPool& pool) {
  run(pass, plane, pool, true);
}

template void run_forward<float>(const AxisPass&, dwt::PlaneSpan<float>, ThreadPool&);
template void run_inverse<float>(const AxisPass&, dwt::PlaneSpan<float>, ThreadPool&);
template void run_forward<std::int32_t>(const AxisPass&, dwt::PlaneSpan<std::int32_t>, ThreadPool&);
template void run_inverse<std::int32_t>(const AxisPass&, dwt::PlaneSpan<std::int32_t>, ThreadPool&);

}  // namespace dwt_cpu
