#pragma once
// The shared test matrix of the wavelet engine: sizes from the issue, both origin parities on each
// axis, every kernel and boundary scheme, up to the maximal level count.
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dwt/boundary.h"
#include "dwt/geometry.h"
#include "dwt/kernel.h"
#include "dwt_reference.h"

namespace testmatrix {

inline const std::vector<int>& sizes() {
  static const std::vector<int> s = {1, 2, 3, 4, 5, 7, 8, 13, 64, 257, 1000};
  return s;
}

struct Shape {
  int w, h;
};

// Every square size, plus every pairing in which one side is small; large non-square pairings add
// little over their square and small-side cousins.
inline std::vector<Shape> shapes(int max_side = 1000) {
  std::vector<Shape> out;
  for (int w : sizes())
    for (int h : sizes())
      if (w <= max_side && h <= max_side && (w == h || std::min(w, h) <= 13)) out.push_back({w, h});
  return out;
}

inline const std::vector<dwt::Origin>& origins() {
  static const std::vector<dwt::Origin> o = {{0, 0}, {1, 0}, {0, 1}, {3, 5}};
  return o;
}

inline ref::Ext to_ref(dwt::Boundary b) {
  switch (b) {
    case dwt::Boundary::Symmetric:
      return ref::Ext::Sym;
    case dwt::Boundary::Periodic:
      return ref::Ext::Per;
    case dwt::Boundary::Zero:
      return ref::Ext::Zero;
  }
  return ref::Ext::Sym;
}

inline ref::Filter to_ref(dwt::KernelId k) {
  switch (k) {
    case dwt::KernelId::Irreversible97:
      return ref::Filter::F97;
    case dwt::KernelId::Haar:
      return ref::Filter::Haar;
    default:
      return ref::Filter::F53;
  }
}

// Integer-valued samples in [0, 255], deterministic per seed.
inline std::vector<float> samples(int w, int h, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<float> v(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (auto& x : v) x = static_cast<float>(rng() % 256);
  return v;
}

inline std::string describe(const char* kernel, dwt::Boundary b, Shape s, dwt::Origin o, int levels) {
  std::ostringstream os;
  os << "kernel " << kernel << ", " << dwt::boundary_name(b) << ", " << s.w << "x" << s.h << " at origin (" << o.x
     << "," << o.y << "), " << levels << " levels";
  return os.str();
}

// Whether forward then inverse must reproduce the input: whole-sample symmetric extension with the
// symmetric filter banks always does (that is why JPEG 2000 uses it); periodic does when every
// transformed length is even; Haar needs no extension only when every pair is complete.
inline bool perfect_reconstruction(dwt::KernelId k, dwt::Boundary b, Shape s, dwt::Origin o, int levels) {
  const auto geo = dwt::decomposition(s.w, s.h, o, levels);
  auto every_axis = [&](auto pred) {
    for (const auto& g : geo)
      for (const auto& a : {g.x, g.y})
        if (a.length > 1 && !pred(a)) return false;
    return true;
  };
  const bool even_lengths = every_axis([](const dwt::AxisSpan& a) { return a.length % 2 == 0; });
  const bool complete_pairs = every_axis([](const dwt::AxisSpan& a) { return a.length % 2 == 0 && a.parity() == 0; });
  if (k == dwt::KernelId::Haar && complete_pairs) return true;  // Haar then never reads the extension
  if (b == dwt::Boundary::Periodic) return even_lengths;
  if (k == dwt::KernelId::Haar) return false;
  if (b == dwt::Boundary::Symmetric) return true;
  return every_axis([](const dwt::AxisSpan&) { return false; });  // zero: only with nothing to extend
}

}  // namespace testmatrix
