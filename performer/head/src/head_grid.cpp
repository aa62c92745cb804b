#include "head_grid.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace performer::detail {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Samples of the inverse cumulative distribution of `density` over [lo, hi]: where to put points so
// that their spacing is inversely proportional to the density. Tabulated and integrated in double
// with the trapezoid rule, then inverted by linear interpolation: smooth and deterministic.
class DensityWarp {
 public:
  DensityWarp(double lo, double hi, const std::function<double(double)>& density) : lo_(lo), hi_(hi) {
    constexpr int kSamples = 20000;
    cdf_.resize(kSamples + 1);
    cdf_[0] = 0.0;
    const double h = (hi - lo) / kSamples;
    double prev = density(lo);
    for (int i = 1; i <= kSamples; ++i) {
      const double next = density(lo + h * i);
      cdf_[i] = cdf_[i - 1] + 0.5 * (prev + next) * h;
      prev = next;
    }
    for (double& c : cdf_) c /= cdf_.back();
  }
  // The x whose cumulative share is t in [0, 1].
  double at(double t) const {
    const auto it = std::lower_bound(cdf_.begin(), cdf_.end(), t);
    if (it == cdf_.begin()) return lo_;
    if (it == cdf_.end()) return hi_;
    const auto i = static_cast<std::size_t>(it - cdf_.begin());
    const double c0 = cdf_[i - 1], c1 = cdf_[i];
    const double f = c1 > c0 ? (t - c0) / (c1 - c0) : 0.0;
    const double h = (hi_ - lo_) / static_cast<double>(cdf_.size() - 1);
    return lo_ + h * (static_cast<double>(i - 1) + f);
  }

 private:
  double lo_, hi_;
  std::vector<double> cdf_;
};

double bump(double x, double centre, double width) {
  const double t = (x - centre) / width;
  return std::exp(-t * t);
}

// Latitude of a point of the midline plane, seen from the surface centre.
double latitude(const HeadLandmarks& m, double y, double z) {
  const double dy = y - m.centre.y, dz = z - m.centre.z;
  return std::acos(dy / std::sqrt(dy * dy + dz * dz));
}

}  // namespace

HeadGrid make_head_grid(const HeadLandmarks& m, int rings, int segments, int mouth_rows, float focus) {
  HeadGrid g;
  const double f = focus;
  const double eyes = latitude(m, m.eye.y, 0.09), nose = latitude(m, 0.02, 0.12);
  const double chin = latitude(m, -0.05, 0.085);
  g.mouth_theta = static_cast<float>(latitude(m, m.mouth_y, 0.10));
  const double mouth = g.mouth_theta;
  // Rows: extra density over eyes and brows, nose, lips and chin, where the shapes and the poses
  // have detail; the cranium and neck get what is left.
  const DensityWarp rows(0.0, std::numbers::pi, [&](double t) {
    return 1.0 + f * (3.2 * bump(t, eyes, 0.14) + 1.0 * bump(t, nose, 0.12) + 3.0 * bump(t, mouth, 0.15) +
                      0.5 * bump(t, chin, 0.15));
  });
  std::vector<double> theta;
  for (int j = 0; j < rings; ++j) theta.push_back(rows.at((j + 1.0) / (rings + 1.0)));

  // The mouth line: 2K+1 rows a few tenths of a millimetre apart replace the warp's rows there.
  // Keep the neighbours at least about half a row spacing clear of them, so no row pair is closer
  // than the slit's own spacing.
  const double step = m.slit_step;
  std::size_t nearest = 0;
  for (std::size_t j = 1; j < theta.size(); ++j)
    if (std::abs(theta[j] - mouth) < std::abs(theta[nearest] - mouth)) nearest = j;
  const double spacing = nearest + 1 < theta.size() ? theta[nearest + 1] - theta[nearest] : step;
  const double clear = mouth_rows * step + 0.6 * spacing;
  std::vector<double> kept;
  for (const double t : theta)
    if (std::abs(t - mouth) >= clear) kept.push_back(t);
  std::vector<std::pair<double, int>> all;
  for (const double t : kept) all.emplace_back(t, kNotSlit);
  for (int k = -mouth_rows; k <= mouth_rows; ++k) all.emplace_back(mouth + k * step, k);
  std::sort(all.begin(), all.end());
  for (const auto& [t, k] : all) {
    g.theta.push_back(static_cast<float>(t));
    g.slit.push_back(k);
  }

  // Columns: dense over the face (phi near 0) and again over the eyes.
  const double eye_phi = std::atan2(m.eye.x, m.eye.z + m.eye_shell_axes.z);
  const DensityWarp cols(-std::numbers::pi, std::numbers::pi, [&](double p) {
    return 1.0 + f * (2.5 * bump(p, 0.0, 0.6) + 1.5 * (bump(p, eye_phi, 0.14) + bump(p, -eye_phi, 0.14)));
  });
  g.phi.assign(static_cast<std::size_t>(segments), 0.0f);
  const int half = segments / 2;
  for (int c = 0; c <= half; ++c) {
    // Column c at share 0.5 + c / segments; c = half lands on the back (phi = +-pi). Mirrored
    // explicitly so the two sides are exactly symmetric.
    const float p = c == half ? kPi : static_cast<float>(cols.at(0.5 + static_cast<double>(c) / segments));
    g.phi[static_cast<std::size_t>(c)] = p;
    if (c > 0 && c < half) g.phi[static_cast<std::size_t>(segments - c)] = -p;
  }
  return g;
}

std::vector<HeadVertexParam> HeadGrid::vertex_params() const {
  std::vector<HeadVertexParam> out(vertex_count());
  out.front() = {0.0f, 0.0f, kNotSlit};
  out.back() = {kPi, 0.0f, kNotSlit};
  for (std::size_t r = 0; r < rows(); ++r)
    for (std::size_t c = 0; c < columns(); ++c) out[vertex(r, c)] = {theta[r], phi[c], slit[r]};
  return out;
}

std::vector<std::uint32_t> HeadGrid::triangles() const {
  std::vector<std::uint32_t> t;
  const std::size_t n = columns();
  const auto top = std::uint32_t{0}, bottom = static_cast<std::uint32_t>(vertex_count() - 1);
  t.reserve(6 * n * rows());
  // Seen from outside, phi grows to the right and theta downward, so (upper-left, lower-left,
  // lower-right) is counter-clockwise.
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t c1 = (c + 1) % n;
    t.insert(t.end(), {top, vertex(0, c), vertex(0, c1)});
  }
  for (std::size_t r = 0; r + 1 < rows(); ++r) {
    for (std::size_t c = 0; c < n; ++c) {
      const std::size_t c1 = (c + 1) % n;
      const std::uint32_t a = vertex(r, c), b = vertex(r, c1), d = vertex(r + 1, c), e = vertex(r + 1, c1);
      // Columns 0..n/2-1 start on the +X side: split those quads from upper-left to lower-right,
      // the mirror-image quads from upper-right to lower-left.
      if (c < n / 2)
        t.insert(t.end(), {a, d, e, a, e, b});
      else
        t.insert(t.end(), {a, d, b, b, d, e});
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t c1 = (c + 1) % n;
    t.insert(t.end(), {vertex(rows() - 1, c), bottom, vertex(rows() - 1, c1)});
  }
  return t;
}

}  // namespace performer::detail
