#include "axis_pass.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "lifting_simd.h"
#include "lifting_wide.h"
#include "row_lifting.h"
#include "strip_lifting.h"

namespace dwt_cpu {
namespace {

// Vertical strips copy contiguous runs of columns: wide enough to stream whole cache lines and fill
// vectors, small enough that a tall strip stays in L2. Horizontal passes lift each row in place of
// a strip (see run_rows), a block of rows per task.
constexpr std::size_t kVerticalLanes = 64;
constexpr std::size_t kRowsPerTask = 16;
// How far ahead the vertical gather prefetches.
constexpr int kPrefetchLines = 8;

struct Layout {
  int n;       // samples along the axis
  int lanes;   // independent signals (rows for horizontal, columns for vertical)
  int pad;     // extension lines on each side of the strip
  int parity;  // reference-grid parity of the first sample
  int low;     // low-pass count
  std::size_t strip_lanes;
};

Layout layout_of(const AxisPass& p) {
  const bool h = p.axis == Axis::Horizontal;
  return Layout{p.span.length,
                h ? p.region_height : p.region_width,
                static_cast<int>(p.kernel.steps.size()),
                p.span.parity(),
                p.span.low_count(),
                h ? kRowsPerTask : kVerticalLanes};
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

// A run of a horizontal inverse's gather: signal[dst, dst + length) = row[src, src + length), or
// zeros where src < 0 (the extension's zero samples).
struct GatherRun {
  int dst, src, length;
};

// The runs of one class's signal, whose sample j is at extended position first + 2 j.
std::vector<GatherRun> gather_runs(const std::vector<int>& map, int first, int size) {
  std::vector<GatherRun> runs;
  for (int j = 0; j < size; ++j) {
    const int src = map[static_cast<std::size_t>(first + 2 * j)];
    if (!runs.empty()) {
      GatherRun& last = runs.back();
      const bool continues = src < 0 ? last.src < 0 : last.src >= 0 && src == last.src + last.length;
      if (continues) {
        ++last.length;
        continue;
      }
    }
    runs.push_back(GatherRun{j, src, 1});
  }
  return runs;
}

template <class T>
void gather(const std::vector<GatherRun>& runs, const T* row, T* signal) {
  for (const GatherRun& r : runs) {
    if (r.src < 0)
      std::fill_n(signal + r.dst, r.length, T(0));
    else
      std::copy_n(row + r.src, r.length, signal + r.dst);
  }
}

// Horizontal pass: each row is split into its low and high components (with extension), lifted
// there, and the interior copied out contiguously: low half then high half (forward), or
// re-interleaved (inverse).
template <class T>
void run_rows(const Layout& L, const AxisPass& p, dwt::PlaneSpan<T> plane, base::ThreadPool& pool, bool inverse,
              const std::vector<int>& map) {
  const int total = L.n + 2 * L.pad;
  const int first_low = (L.parity - L.pad) & 1 ? 1 : 0;  // extended position 0 is low iff its class is 0
  const int low_size = (total - first_low + 1) / 2, high_size = (total - (1 - first_low) + 1) / 2;
  // Interior samples start at extended position pad: the first low/high component index there.
  const int low_skip = (L.pad - first_low + 1) / 2, high_skip = (L.pad - (1 - first_low) + 1) / 2;
  const std::size_t tasks = (static_cast<std::size_t>(L.lanes) + kRowsPerTask - 1) / kRowsPerTask;
  // The inverse's gathers as runs: each class's coefficients are contiguous in the Mallat-ordered
  // row apart from the extension, so a row is gathered in a few copies instead of a map lookup and
  // a branch per sample.
  const std::vector<GatherRun> low_runs = inverse ? gather_runs(map, first_low, low_size) : std::vector<GatherRun>{};
  const std::vector<GatherRun> high_runs =
      inverse ? gather_runs(map, 1 - first_low, high_size) : std::vector<GatherRun>{};
  pool.parallel_for(tasks, [&](std::size_t task) {
    thread_local std::vector<T> scratch;
    scratch.resize(static_cast<std::size_t>(low_size + high_size));
    const SplitSignal<T> sig{scratch.data(), scratch.data() + low_size, low_size, high_size, first_low};
    const int y_end = std::min(L.lanes, static_cast<int>((task + 1) * kRowsPerTask));
    for (int y = static_cast<int>(task * kRowsPerTask); y < y_end; ++y) {
      T* row = plane.row(y);
      auto fetch = [&](int position) {
        const int src = map[static_cast<std::size_t>(position)];
        return src < 0 ? T(0) : row[src];
      };
      if (inverse) {
        gather(low_runs, row, sig.low);
        gather(high_runs, row, sig.high);
      } else {
        // Pair j holds extended positions 2j and 2j + 1 (low[j] and high[j] in some order); where
        // both lie inside the row, at samples 2j - pad and 2j + 1 - pad, one interleaved load splits
        // them. The pairs before and after, in the extension, go through the map.
        const int pairs = std::min(low_size, high_size);
        const int j0 = std::min(pairs, (L.pad + 1) / 2);
        const int j1 = std::max(j0, std::min(pairs, (L.n + L.pad - 2) / 2 + 1));
        for (int j = 0; j < j0; ++j) sig.low[j] = fetch(first_low + 2 * j), sig.high[j] = fetch(1 - first_low + 2 * j);
        for (int j = j1; j < low_size; ++j) sig.low[j] = fetch(first_low + 2 * j);
        for (int j = j1; j < high_size; ++j) sig.high[j] = fetch(1 - first_low + 2 * j);
        T* even = first_low == 0 ? sig.low : sig.high;
        T* odd = first_low == 0 ? sig.high : sig.low;
        simd::deinterleave(row + 2 * j0 - L.pad, even + j0, odd + j0, static_cast<std::size_t>(j1 - j0));
      }
      if (inverse) {
        lift_inverse(p.kernel, sig);
        // Sample e is the next of its class's lifted signal every two samples: the interior goes
        // back as one interleave of the classes of samples 0 and 1.
        auto lifted = [&](int e) {
          const int position = e + L.pad;
          return ((position - first_low) & 1) == 0 ? sig.low + ((position - first_low) >> 1)
                                                   : sig.high + ((position - 1 + first_low) >> 1);
        };
        const T* even = lifted(0);
        simd::interleave(even, lifted(1), row, static_cast<std::size_t>(L.n / 2));
        if (L.n % 2 != 0) row[L.n - 1] = even[L.n / 2];
      } else if constexpr (std::is_floating_point_v<T>) {
        // The gains on the way out: one pass over the row fewer.
        lift_forward_steps(p.kernel, sig);
        auto put = [](const T* from, int count, T* to, double gain) {
          if (gain != 1.0)
            simd::scale_copy(from, to, static_cast<T>(gain), static_cast<std::size_t>(count));
          else
            std::copy_n(from, count, to);
        };
        put(sig.low + low_skip, L.low, row, p.kernel.low_gain);
        put(sig.high + high_skip, L.n - L.low, row + L.low, p.kernel.high_gain);
      } else {
        lift_forward(p.kernel, sig);
        std::copy_n(sig.low + low_skip, L.low, row);
        std::copy_n(sig.high + high_skip, L.n - L.low, row + L.low);
      }
    }
  });
}

// Line b of a vertical strip, gathered from its plane row (map[b]; -1: zeros) and multiplied by
// `gain` unless that is 1, with the line kPrefetchLines ahead asked for: each line is a short run
// of a row a plane's width from the last, which the hardware prefetcher does not follow.
template <class T>
void gather_line(const Strip<T>& strip, int b, const std::vector<int>& map, dwt::PlaneSpan<T> plane, int lane0,
                 T gain) {
  T* line = strip.line(b);
  const int src = map[static_cast<std::size_t>(b)];
  if (src < 0) {
    std::fill(line, line + strip.lanes, T(0));
    return;
  }
  if (b + kPrefetchLines < strip.lines) {
    const int ahead = map[static_cast<std::size_t>(b + kPrefetchLines)];
    if (ahead >= 0) {
      const char* from = reinterpret_cast<const char*>(plane.row(ahead) + lane0);
      for (std::size_t k = 0; k < strip.lanes * sizeof(T); k += 64) __builtin_prefetch(from + k);
    }
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (gain != T(1)) return simd::scale_copy(plane.row(src) + lane0, line, gain, strip.lanes);
  }
  std::memcpy(line, plane.row(src) + lane0, strip.lanes * sizeof(T));
}

// How many lines a vertical pass gathers between two advances of its lifting: few enough that the
// lines a step touches are still in the first-level cache.
constexpr int kStreamLines = 8;

// The vertical pass, strip by strip: a strip's lines are gathered top to bottom (the inverse's
// with its gains undone on the way) and lifted as they arrive (StreamingLift), and each finished
// line goes to its row (the forward's to its Mallat row, with its gain applied on the way) as soon
// as no later gather reads that row. A line then crosses the cache about once, where gathering the
// whole strip, lifting it step by step and scaling it class by class crossed it six times, and
// many lines leave while they are still cached. The arithmetic is lift_forward's or
// lift_inverse's, in the same order: the results are the same to the bit.
template <class T>
void run_columns(const Layout& L, const AxisPass& p, dwt::PlaneSpan<T> plane, base::ThreadPool& pool,
                 const std::vector<int>& map, bool inverse) {
  const int lines = L.n + 2 * L.pad;
  const std::size_t strips = (static_cast<std::size_t>(L.lanes) + L.strip_lanes - 1) / L.strip_lanes;
  // Line 0 holds position -pad; its class follows from the parity of the first sample.
  const int first_class = (L.parity - L.pad) & 1;
  // first_read[b]: the lowest plane row that lines b, b + 1, ... read (the bottom extension
  // re-reads rows near the end); a finished line may overwrite its row only below it.
  std::vector<int> first_read(static_cast<std::size_t>(lines) + 1, std::numeric_limits<int>::max());
  for (int b = lines - 1; b >= 0; --b) {
    const int src = map[static_cast<std::size_t>(b)];
    first_read[static_cast<std::size_t>(b)] =
        std::min(first_read[static_cast<std::size_t>(b) + 1], src < 0 ? std::numeric_limits<int>::max() : src);
  }
  // Per class (0 low, 1 high): the gain the forward pass applies on the way out, or the factor
  // the inverse applies on the way in; 1 for integers and for a gain of 1.
  T gain_out[2] = {T(1), T(1)}, gain_in[2] = {T(1), T(1)};
  if constexpr (std::is_floating_point_v<T>) {
    const double gains[2] = {p.kernel.low_gain, p.kernel.high_gain};
    for (int c = 0; c < 2; ++c)
      if (gains[c] != 1.0) (inverse ? gain_in[c] : gain_out[c]) = static_cast<T>(inverse ? 1.0 / gains[c] : gains[c]);
  }

  pool.parallel_for(strips, [&](std::size_t s) {
    thread_local std::vector<T> scratch;
    const std::size_t W = L.strip_lanes;
    scratch.resize(static_cast<std::size_t>(lines) * W);
    const int lane0 = static_cast<int>(s * W);
    const std::size_t lanes = std::min<std::size_t>(W, static_cast<std::size_t>(L.lanes - lane0));
    const Strip<T> strip{scratch.data(), lines, lanes, W, first_class};
    StreamingLift<T> lift(p.kernel, strip, inverse);
    // The next sample of each class to go out (interior line e sits at strip line e + pad).
    int next_out[2] = {L.parity & 1, (1 + L.parity) & 1};
    auto put = [&](int e, int c) {
      const T* line = strip.line(e + L.pad);
      T* row = plane.row(inverse ? e : mallat_index(L, e)) + lane0;
      if constexpr (std::is_floating_point_v<T>) {
        if (gain_out[c] != T(1)) return simd::scale_copy(line, row, gain_out[c], lanes);
      }
      std::memcpy(row, line, lanes * sizeof(T));
    };
    for (int gathered = 0; gathered < lines;) {
      const int until = std::min(lines, gathered + kStreamLines);
      for (; gathered < until; ++gathered)
        gather_line(strip, gathered, map, plane, lane0, gain_in[strip.class_of(gathered)]);
      const int finished = lift.advance(gathered);
      const int free_below = first_read[static_cast<std::size_t>(gathered)];
      for (int c = 0; c < 2; ++c)
        for (int& e = next_out[c]; e < L.n && e + L.pad < finished && (inverse ? e : mallat_index(L, e)) < free_below;
             e += 2)
          put(e, c);
    }
  });
}

template <class T>
void run(const AxisPass& p, dwt::PlaneSpan<T> plane, base::ThreadPool& pool, bool inverse) {
  const Layout L = layout_of(p);
  if (L.n == 0 || L.lanes == 0) return;
  if (L.n == 1) return single_sample(p, plane, inverse);

  const std::vector<int> map = source_map(L, p.boundary, inverse);
  if (p.axis == Axis::Horizontal) return run_rows(L, p, plane, pool, inverse, map);
  run_columns(L, p, plane, pool, map, inverse);
}

}  // namespace

template <class T>
void run_forward(const AxisPass& pass, dwt::PlaneSpan<T> plane, base::ThreadPool& pool) {
  run(pass, plane, pool, false);
}
template <class T>
void run_inverse(const AxisPass& pass, dwt::PlaneSpan<T> plane, base::ThreadPool& pool) {
  run(pass, plane, pool, true);
}

template void run_forward<float>(const AxisPass&, dwt::PlaneSpan<float>, base::ThreadPool&);
template void run_inverse<float>(const AxisPass&, dwt::PlaneSpan<float>, base::ThreadPool&);
template void run_forward<std::int32_t>(const AxisPass&, dwt::PlaneSpan<std::int32_t>, base::ThreadPool&);
template void run_inverse<std::int32_t>(const AxisPass&, dwt::PlaneSpan<std::int32_t>, base::ThreadPool&);
template void run_forward<double>(const AxisPass&, dwt::PlaneSpan<double>, base::ThreadPool&);
template void run_inverse<double>(const AxisPass&, dwt::PlaneSpan<double>, base::ThreadPool&);
template void run_forward<std::int64_t>(const AxisPass&, dwt::PlaneSpan<std::int64_t>, base::ThreadPool&);
template void run_inverse<std::int64_t>(const AxisPass&, dwt::PlaneSpan<std::int64_t>, base::ThreadPool&);

}  // namespace dwt_cpu
