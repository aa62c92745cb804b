#pragma once
// An independent float64 model of the transforms, for tests only. It shares no code with the
// backends: literal published filter taps, its own boundary extension and subband geometry, and
// direct convolution (analysis) and direct synthesis summation (inverse) instead of lifting.
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ref {

enum class Ext { Sym, Per, Zero };
enum class Filter { F97, F53, Haar };

// Taps indexed by k = -4..4, as maps so the support is explicit.
struct FilterBank {
  std::map<int, double> h;   // analysis low:  L(e) = sum_k h(k) x(e - k), e even on the canvas
  std::map<int, double> g;   // analysis high: H(e) = sum_k g(k) x(e - k), e odd on the canvas
  std::map<int, double> hs;  // synthesis weight of a low coefficient at s on sample m: hs(m - s)
  std::map<int, double> gs;  // synthesis weight of a high coefficient at s on sample m: gs(m - s)
};

inline FilterBank make_bank(Filter f) {
  FilterBank b;
  switch (f) {
    case Filter::F97: {
      // CDF 9/7 with JPEG 2000 normalisation (T.800 Table F.4's lifting, expanded; also e.g.
      // Unser & Blu, "Mathematical properties of the JPEG2000 wavelet filters", 2003).
      const double h[] = {0.602949018236358, 0.266864118442875, -0.078223266528990, -0.016864118442875,
                          0.026748757410810};
      const double g[] = {1.115087052457000, -0.591271763114250, -0.057543526228500, 0.091271763114250};
      for (int k = 0; k <= 4; ++k) b.h[k] = b.h[-k] = h[k];
      for (int k = 0; k <= 3; ++k) b.g[k] = b.g[-k] = g[k];
      // Synthesis filters of the biorthogonal pair: hs(n) = (-1)^n g(n), gs(n) = (-1)^n h(n).
      for (int k = -3; k <= 3; ++k) b.hs[k] = ((k & 1) ? -1 : 1) * b.g[k];
      for (int k = -4; k <= 4; ++k) b.gs[k] = ((k & 1) ? -1 : 1) * b.h[k];
      break;
    }
    case Filter::F53:
      b.h = {{-2, -0.125}, {-1, 0.25}, {0, 0.75}, {1, 0.25}, {2, -0.125}};
      b.g = {{-1, -0.5}, {0, 1.0}, {1, -0.5}};
      b.hs = {{-1, 0.5}, {0, 1.0}, {1, 0.5}};
      b.gs = {{-2, -0.125}, {-1, -0.25}, {0, 0.75}, {1, -0.25}, {2, -0.125}};
      break;
    case Filter::Haar:
      // L(e) = (x(e) + x(e+1)) / 2, H(e) = x(e) - x(e-1).
      b.h = {{0, 0.5}, {-1, 0.5}};
      b.g = {{0, 1.0}, {1, -1.0}};
      // x(m) = L(m) - H(m+1)/2 for even m; x(m) = L(m-1) + H(m)/2 for odd m.
      b.hs = {{0, 1.0}, {1, 1.0}};
      b.gs = {{-1, -0.5}, {0, 0.5}};
      break;
  }
  return b;
}

// The bank of a filter, built once: the tests transform thousands of rows, and building four maps
// per row made the reference most of dwt_cpu_test's time (and 100 s of it under ASan).
inline const FilterBank& bank(Filter f) {
  static const FilterBank banks[] = {make_bank(Filter::F97), make_bank(Filter::F53), make_bank(Filter::Haar)};
  return banks[static_cast<int>(f)];
}

// A tap map as a dense array over k = -4..4 (0 outside the support), for the inner loops.
struct DenseTaps {
  double w[9] = {};
  explicit DenseTaps(const std::map<int, double>& taps) {
    for (const auto& [k, v] : taps) w[k + 4] = v;
  }
  double operator[](long k) const { return k < -4 || k > 4 ? 0.0 : w[k + 4]; }
};

// Value of the extended signal at index i (0-based within the signal).
inline double extended(const std::vector<double>& x, long i, Ext e) {
  const long n = static_cast<long>(x.size());
  if (i >= 0 && i < n) return x[static_cast<std::size_t>(i)];
  if (e == Ext::Zero) return 0.0;
  if (e == Ext::Per) return x[static_cast<std::size_t>(((i % n) + n) % n)];
  if (n == 1) return x[0];
  // Whole-sample symmetric: reflect about 0 and n-1 until inside.
  while (i < 0 || i >= n) {
    if (i < 0) i = -i;
    if (i >= n) i = 2 * (n - 1) - i;
  }
  return x[static_cast<std::size_t>(i)];
}

inline long low_count(long start, long len) {
  auto ceil_half = [](long v) { return (v + 1) / 2; };  // v >= 0
  return ceil_half(start + len) - ceil_half(start);
}

// One level of 1-D analysis of x whose first sample sits at canvas coordinate `start`;
// result: low-pass samples then high-pass samples.
inline std::vector<double> analyse(const std::vector<double>& x, long start, Filter f, Ext e) {
  const long n = static_cast<long>(x.size());
  if (n == 0) return {};
  if (n == 1) return {(start & 1) ? 2.0 * x[0] : x[0]};  // T.800 F.4.7: a lone odd sample doubles
  const FilterBank& b = bank(f);
  const DenseTaps low_analysis(b.h), high_analysis(b.g);
  std::vector<double> lo, hi;
  for (long i = 0; i < n; ++i) {
    const bool odd = ((start + i) & 1) != 0;
    const DenseTaps& taps = odd ? high_analysis : low_analysis;
    double acc = 0.0;
    for (long k = -4; k <= 4; ++k)
      if (taps[k] != 0.0) acc += taps[k] * extended(x, i - k, e);
    (odd ? hi : lo).push_back(acc);
  }
  lo.insert(lo.end(), hi.begin(), hi.end());
  return lo;
}

// One level of 1-D synthesis: interleave low/high by canvas parity, extend that sequence, and sum
// each coefficient's synthesis filter (equation 4.13 of the thesis).
inline std::vector<double> synthesise(const std::vector<double>& c, long start, Filter f, Ext e) {
  const long n = static_cast<long>(c.size());
  if (n == 0) return {};
  if (n == 1) return {(start & 1) ? 0.5 * c[0] : c[0]};
  const long nl = low_count(start, n);
  std::vector<double> y(static_cast<std::size_t>(n));
  long il = 0, ih = nl;
  for (long i = 0; i < n; ++i)
    y[static_cast<std::size_t>(i)] =
        ((start + i) & 1) ? c[static_cast<std::size_t>(ih++)] : c[static_cast<std::size_t>(il++)];
  const FilterBank& b = bank(f);
  const DenseTaps low_synthesis(b.hs), high_synthesis(b.gs);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (long m = 0; m < n; ++m) {
    double acc = 0.0;
    for (long s = m - 4; s <= m + 4; ++s) {
      const bool odd = ((start + s) & 1) != 0;  // class of the position, after extension
      const double w = (odd ? high_synthesis : low_synthesis)[m - s];
      if (w != 0.0) acc += w * extended(y, s, e);
    }
    x[static_cast<std::size_t>(m)] = acc;
  }
  return x;
}

struct Plane {
  int w = 0, h = 0;
  std::vector<double> v;
  double& at(int x, int y) {
    return v[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
  }
};

// 2-D, `levels` levels, Mallat layout, by rows and columns of the shrinking LL region.
inline void transform(Plane& p, long x0, long y0, int levels, Filter f, Ext e, bool inverse) {
  struct Region {
    long sx, sy, w, h;
  };
  std::vector<Region> regions;
  Region r{x0, y0, p.w, p.h};
  for (int d = 0; d < levels; ++d) {
    regions.push_back(r);
    r = Region{(r.sx + 1) / 2, (r.sy + 1) / 2, low_count(r.sx, r.w), low_count(r.sy, r.h)};
  }
  auto do_rows = [&](const Region& g) {
    for (long y = 0; y < g.h; ++y) {
      std::vector<double> row(static_cast<std::size_t>(g.w));
      for (long x = 0; x < g.w; ++x) row[static_cast<std::size_t>(x)] = p.at(static_cast<int>(x), static_cast<int>(y));
      row = inverse ? synthesise(row, g.sx, f, e) : analyse(row, g.sx, f, e);
      for (long x = 0; x < g.w; ++x) p.at(static_cast<int>(x), static_cast<int>(y)) = row[static_cast<std::size_t>(x)];
    }
  };
  auto do_cols = [&](const Region& g) {
    for (long x = 0; x < g.w; ++x) {
      std::vector<double> col(static_cast<std::size_t>(g.h));
      for (long y = 0; y < g.h; ++y) col[static_cast<std::size_t>(y)] = p.at(static_cast<int>(x), static_cast<int>(y));
      col = inverse ? synthesise(col, g.sy, f, e) : analyse(col, g.sy, f, e);
      for (long y = 0; y < g.h; ++y) p.at(static_cast<int>(x), static_cast<int>(y)) = col[static_cast<std::size_t>(y)];
    }
  };
  if (!inverse) {
    for (const auto& g : regions) {
      do_cols(g);
      do_rows(g);
    }
  } else {
    for (auto it = regions.rbegin(); it != regions.rend(); ++it) {
      do_rows(*it);
      do_cols(*it);
    }
  }
}

// T.800's reversible 5/3 written literally on canvas coordinates (F.4.8.1, equations F-9 and F-10,
// periodic symmetric extension of F.4.7), as an exact integer model.
inline std::vector<long> rev53_analyse(const std::vector<long>& x, long i0) {
  const long n = static_cast<long>(x.size()), i1 = i0 + n;
  if (n == 0) return {};
  if (n == 1) return {(i0 & 1) ? 2 * x[0] : x[0]};
  auto X = [&](long i) {  // PSE on canvas coordinates
    long k = i - i0;
    while (k < 0 || k >= n) {
      if (k < 0) k = -k;
      if (k >= n) k = 2 * (n - 1) - k;
    }
    return x[static_cast<std::size_t>(k)];
  };
  auto floordiv = [](long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  std::map<long, long> Y;
  for (long i = i0 - 1; i < i1 + 1; ++i)
    if (i & 1) Y[i] = X(i) - floordiv(X(i - 1) + X(i + 1), 2);
  for (long i = i0; i < i1; ++i)
    if (!(i & 1)) Y[i] = X(i) + floordiv(Y.at(i - 1) + Y.at(i + 1) + 2, 4);
  std::vector<long> lo, hi;
  for (long i = i0; i < i1; ++i) ((i & 1) ? hi : lo).push_back(Y.at(i));
  lo.insert(lo.end(), hi.begin(), hi.end());
  return lo;
}

// The exact model applied 2-D in the standard's order (columns then rows at each level) to a
// w x h plane at (x0, y0) on the canvas, leaving the Mallat layout the backends leave.
inline std::vector<long> rev53_analyse_2d(std::vector<long> v, long w0, long h0, long x0, long y0, int levels) {
  long sx = x0, sy = y0, w = w0, h = h0;
  for (int d = 0; d < levels; ++d) {
    for (long x = 0; x < w; ++x) {
      std::vector<long> col(static_cast<std::size_t>(h));
      for (long y = 0; y < h; ++y) col[static_cast<std::size_t>(y)] = v[static_cast<std::size_t>(y * w0 + x)];
      col = rev53_analyse(col, sy);
      for (long y = 0; y < h; ++y) v[static_cast<std::size_t>(y * w0 + x)] = col[static_cast<std::size_t>(y)];
    }
    for (long y = 0; y < h; ++y) {
      std::vector<long> row(v.begin() + y * w0, v.begin() + y * w0 + w);
      row = rev53_analyse(row, sx);
      std::copy(row.begin(), row.end(), v.begin() + y * w0);
    }
    const long nw = low_count(sx, w), nh = low_count(sy, h);
    sx = (sx + 1) / 2, sy = (sy + 1) / 2, w = nw, h = nh;
  }
  return v;
}

}  // namespace ref
