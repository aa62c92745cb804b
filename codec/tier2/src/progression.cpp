#include "codec/tier2/progression.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace codec::t2 {

namespace {

[[noreturn]] void bad_geometry(const std::string& what) { throw std::invalid_argument("progression: " + what); }

bool has_packets(const ResolutionGeometry& g) { return g.precincts_wide > 0 && g.precincts_high > 0; }

// sampling * 2^shift, refusing what int64 cannot hold (PP <= 15 and NL <= 32 always fit).
std::int64_t scaled(int sampling, int shift) {
  if (shift < 0 || shift > 62 || sampling > (std::numeric_limits<std::int64_t>::max() >> shift))
    bad_geometry("precinct size on the reference grid overflows");
  return static_cast<std::int64_t>(sampling) << shift;
}

// A precinct's extent on the reference grid: XRsiz * 2^(PPx + NL - r) (resp. y).
std::int64_t grid_size(int sampling, int pp, int nl, int r) { return scaled(sampling, pp + nl - r); }

// The standard's position loops run over every grid point "y = ty0, ..., ty1 - 1" (x alike), but
// its test can only be true at ty0 itself or at a multiple of one of the precinct sizes involved.
// Visiting exactly those points, ascending, gives the same sequence in time proportional to the
// number of precinct boundaries. (Stepping by the smallest size, as the standard's note suggests,
// is the same thing when every size is a multiple of the smallest, i.e. for power-of-two XRsiz.)
std::vector<std::int64_t> candidate_positions(std::int64_t t0, std::int64_t t1, std::vector<std::int64_t> sizes) {
  std::vector<std::int64_t> out;
  if (t0 >= t1 || sizes.empty()) return out;
  std::sort(sizes.begin(), sizes.end());
  sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
  out.push_back(t0);
  for (std::int64_t pos = t0;;) {
    std::int64_t next = std::numeric_limits<std::int64_t>::max();
    for (std::int64_t s : sizes) next = std::min(next, (pos / s + 1) * s);
    if (next >= t1) break;
    out.push_back(next);
    pos = next;
  }
  return out;
}

// B.12.1.3's test along one axis: the position starts a precinct of (c, r), or it is the tile's
// first position and the resolution's origin lies inside a precinct rather than on its edge.
// (try0 * 2^(NL-r) divisible by 2^(PPy+NL-r) is try0 divisible by 2^PPy; the short form cannot overflow.)
bool starts_precinct(std::int64_t pos, std::int64_t tile_origin, std::int64_t size, std::int64_t res_origin, int pp) {
  return pos % size == 0 || (pos == tile_origin && res_origin % (std::int64_t{1} << pp) != 0);
}

// B-20 along one axis: floor(ceil(pos / (XRsiz * 2^(NL-r))) / 2^PPx) - floor(trx0 / 2^PPx).
std::int64_t precinct_coordinate(std::int64_t pos, int sampling, int nl, int r, std::int64_t res_origin, int pp) {
  const std::int64_t per_sample = scaled(sampling, nl - r);
  const std::int64_t in_resolution = (pos + per_sample - 1) / per_sample;
  return (in_resolution >> pp) - (res_origin >> pp);
}

struct Walker {
  int layers;
  std::int64_t tx0, ty0;
  const std::vector<ComponentGeometry>& components;
  std::vector<PacketId>& out;

  // "for the next precinct, k, if one exists ... for each l: packet (l, r, c, k)".
  void visit(int c, int r, std::int64_t x, std::int64_t y) const {
    const ComponentGeometry& comp = components[static_cast<std::size_t>(c)];
    if (r >= static_cast<int>(comp.resolutions.size())) return;
    const ResolutionGeometry& g = comp.resolutions[static_cast<std::size_t>(r)];
    if (!has_packets(g)) return;
    const int nl = static_cast<int>(comp.resolutions.size()) - 1;
    if (!starts_precinct(y, ty0, grid_size(comp.dy, g.ppy, nl, r), g.y0, g.ppy)) return;
    if (!starts_precinct(x, tx0, grid_size(comp.dx, g.ppx, nl, r), g.x0, g.ppx)) return;
    const std::int64_t kx = precinct_coordinate(x, comp.dx, nl, r, g.x0, g.ppx);
    const std::int64_t ky = precinct_coordinate(y, comp.dy, nl, r, g.y0, g.ppy);
    if (kx < 0 || kx >= g.precincts_wide || ky < 0 || ky >= g.precincts_high) return;
    const int k = static_cast<int>(ky * g.precincts_wide + kx);
    for (int l = 0; l < layers; ++l) out.push_back(PacketId{l, r, c, k});
  }

  // Candidate positions along both axes for the (component, resolution) pairs a loop visits.
  template <class Pairs>
  void positions(Pairs pairs, std::int64_t tx1, std::int64_t ty1, std::vector<std::int64_t>& xs,
                 std::vector<std::int64_t>& ys) const {
    std::vector<std::int64_t> sx, sy;
    pairs([&](int c, int r) {
      const ComponentGeometry& comp = components[static_cast<std::size_t>(c)];
      if (r >= static_cast<int>(comp.resolutions.size())) return;
      const ResolutionGeometry& g = comp.resolutions[static_cast<std::size_t>(r)];
      if (!has_packets(g)) return;
      const int nl = static_cast<int>(comp.resolutions.size()) - 1;
      sx.push_back(grid_size(comp.dx, g.ppx, nl, r));
      sy.push_back(grid_size(comp.dy, g.ppy, nl, r));
    });
    xs = candidate_positions(tx0, tx1, std::move(sx));
    ys = candidate_positions(ty0, ty1, std::move(sy));
  }
};

void validate(int layers, std::int64_t tx0, std::int64_t ty0, const std::vector<ComponentGeometry>& components) {
  if (layers < 0) bad_geometry("negative layer count");
  if (tx0 < 0 || ty0 < 0) bad_geometry("negative tile origin");
  for (const ComponentGeometry& comp : components) {
    if (comp.dx < 1 || comp.dy < 1) bad_geometry("component sampling below 1");
    if (comp.resolutions.empty()) bad_geometry("component without resolutions");
    for (const ResolutionGeometry& g : comp.resolutions) {
      if (g.ppx < 0 || g.ppy < 0 || g.ppx > 31 || g.ppy > 31) bad_geometry("precinct exponent out of 0..31");
      if (g.precincts_wide < 0 || g.precincts_high < 0) bad_geometry("negative precinct count");
      if (g.x0 < 0 || g.y0 < 0) bad_geometry("negative resolution origin");
    }
  }
}

}  // namespace

std::vector<PacketId> progression(Order order, int layers, std::int64_t tile_x0, std::int64_t tile_y0,
                                  std::int64_t tile_x1, std::int64_t tile_y1,
                                  const std::vector<ComponentGeometry>& components) {
  validate(layers, tile_x0, tile_y0, components);
  const int ncomp = static_cast<int>(components.size());
  auto levels = [&](int c) { return static_cast<int>(components[static_cast<std::size_t>(c)].resolutions.size()); };
  int max_res = 0;
  std::size_t expected = 0;
  for (int c = 0; c < ncomp; ++c) {
    max_res = std::max(max_res, levels(c));
    for (const ResolutionGeometry& g : components[static_cast<std::size_t>(c)].resolutions)
      expected += static_cast<std::size_t>(layers) * static_cast<std::size_t>(g.precincts_wide) *
                  static_cast<std::size_t>(g.precincts_high);
  }

  std::vector<PacketId> out;
  out.reserve(expected);
  auto all_precincts = [&](int l, int r, int c) {
    if (r >= levels(c)) return;  // a component with fewer levels has no such resolution
    const ResolutionGeometry& g = components[static_cast<std::size_t>(c)].resolutions[static_cast<std::size_t>(r)];
    const int n = g.precincts_wide * g.precincts_high;
    for (int k = 0; k < n; ++k) out.push_back(PacketId{l, r, c, k});
  };
  Walker walk{layers, tile_x0, tile_y0, components, out};
  std::vector<std::int64_t> xs, ys;

  switch (order) {
    case Order::LRCP:  // B.12.1.1
      for (int l = 0; l < layers; ++l)
        for (int r = 0; r < max_res; ++r)
          for (int c = 0; c < ncomp; ++c) all_precincts(l, r, c);
      break;
    case Order::RLCP:  // B.12.1.2
      for (int r = 0; r < max_res; ++r)
        for (int l = 0; l < layers; ++l)
          for (int c = 0; c < ncomp; ++c) all_precincts(l, r, c);
      break;
    case Order::RPCL:  // B.12.1.3: r, y, x, c, l
      for (int r = 0; r < max_res; ++r) {
        walk.positions(
            [&](auto f) {
              for (int c = 0; c < ncomp; ++c) f(c, r);
            },
            tile_x1, tile_y1, xs, ys);
        for (std::int64_t y : ys)
          for (std::int64_t x : xs)
            for (int c = 0; c < ncomp; ++c) walk.visit(c, r, x, y);
      }
      break;
    case Order::PCRL:  // B.12.1.4: y, x, c, r, l
      walk.positions(
          [&](auto f) {
            for (int c = 0; c < ncomp; ++c)
              for (int r = 0; r < levels(c); ++r) f(c, r);
          },
          tile_x1, tile_y1, xs, ys);
      for (std::int64_t y : ys)
        for (std::int64_t x : xs)
          for (int c = 0; c < ncomp; ++c)
            for (int r = 0; r < levels(c); ++r) walk.visit(c, r, x, y);
      break;
    case Order::CPRL:  // B.12.1.5: c, y, x, r, l
      for (int c = 0; c < ncomp; ++c) {
        walk.positions(
            [&](auto f) {
              for (int r = 0; r < levels(c); ++r) f(c, r);
            },
            tile_x1, tile_y1, xs, ys);
        for (std::int64_t y : ys)
          for (std::int64_t x : xs)
            for (int r = 0; r < levels(c); ++r) walk.visit(c, r, x, y);
      }
      break;
    default:
      bad_geometry("unknown progression order");
  }

  // With geometry derived from this tile (B.6) every precinct is reached exactly once, so any
  // other count means geometry that does not belong to the tile.
  if (out.size() != expected)
    bad_geometry("precinct counts do not match the tile: " + std::to_string(out.size()) + " of " +
                 std::to_string(expected) + " packets reached");
  return out;
}

}  // namespace codec::t2
