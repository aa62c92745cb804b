#include "head_shape.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace performer::detail {

namespace {

glm::vec3 direction(float theta, float phi) {
  return {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
}

// The farthest distance along the ray from `origin` at which `inside` still holds: for a solid
// containing the origin that is where the ray leaves it for good, so a dent or a bulge seen edge-on
// still gives one well-defined point per ray. March in from well outside the head, then bisect.
template <typename Inside>
float radial_extent(const glm::vec3& origin, const glm::vec3& d, Inside inside) {
  constexpr float kFar = 0.3f, kStep = 0.002f;
  float r = kFar;
  while (r > 0.0f && !inside(origin + r * d)) r -= kStep;
  if (r <= 0.0f) return 0.0f;
  float in = r, out = r + kStep;
  for (int i = 0; i < 24; ++i) {
    const float mid = 0.5f * (in + out);
    (inside(origin + mid * d) ? in : out) = mid;
  }
  return in;
}

// Smooth maximum (polynomial): a fillet of width k where two solids' surfaces meet, instead of a
// crease.
float smooth_max(float a, float b, float k) {
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::max(a, b) + h * h * k * 0.25f;
}

float cranium_extent(const HeadLandmarks& m, const glm::vec3& d) {
  return radial_extent(m.centre, d, [&m](const glm::vec3& p) {
    const glm::vec3 q = glm::abs(p - m.cranium_centre) / m.cranium_axes;
    const float e = m.cranium_power;
    return std::pow(q.x, e) + std::pow(q.y, e) + std::pow(q.z, e) <= 1.0f;
  });
}

float face_extent(const HeadLandmarks& m, const glm::vec3& d) {
  return radial_extent(m.centre, d, [&m](const glm::vec3& p) {
    // Narrower toward the chin at the front than at the jaw angles at the back.
    const float taper = 1.0f - 0.45f * smoothstep(0.02f, -0.07f, p.y) * smoothstep(-0.01f, 0.07f, p.z);
    const glm::vec3 q = (p - m.face_centre) / (m.face_axes * glm::vec3(taper, 1.0f, 1.0f));
    const float e = m.face_power;
    return std::pow(std::abs(q.x), e) + std::pow(std::abs(q.y), e) + std::pow(std::abs(q.z), e) <= 1.0f;
  });
}

float neck_extent(const HeadLandmarks& m, const glm::vec3& d) {
  return radial_extent(m.centre, d, [&m](const glm::vec3& p) {
    const glm::vec3 q = p - m.neck_centre;
    const float radial = std::sqrt(q.x * q.x + q.z * q.z) / m.neck_radius;
    const float vertical = std::abs(q.y) / m.neck_half_height;
    return std::pow(radial, 6.0f) + std::pow(vertical, 6.0f) <= 1.0f;
  });
}

// Distance from p to the segment a-b, in the face plane.
float segment_distance(float px, float py, float ax, float ay, float bx, float by) {
  const float vx = bx - ax, vy = by - ay;
  const float t = std::clamp(((px - ax) * vx + (py - ay) * vy) / (vx * vx + vy * vy), 0.0f, 1.0f);
  return std::hypot(px - ax - t * vx, py - ay - t * vy);
}

// Forward (z) relief of the face over the base solids at face point (xa = soft_abs(x), y), s metres below
// the mouth line; `slit` the mouth-line row index. Heights from an average adult face.
float face_relief(const HeadLandmarks& m, float xa, float y, float s, int slit, int slit_rows) {
  float dz = 0.0f;
  // Brow ridge, arching over each eye, weaker between the brows; the nasion dip under it.
  const float brow_y = 0.077f + 0.004f * gauss((xa - 0.03f) / 0.02f);
  dz += 0.0045f * gauss((y - brow_y) / 0.0065f) * gauss((xa - 0.028f) / 0.026f);
  dz -= 0.003f * gauss(xa / 0.01f) * gauss((y - 0.062f) / 0.006f);

  // Nose: a ridge growing from the nasion to the tip, then curving back to the base above the lip;
  // nostril wings either side.
  {
    const float tip_y = 0.022f, top_y = 0.064f;
    float h, width;
    if (y >= tip_y) {
      const float t = std::clamp((top_y - y) / (top_y - tip_y), 0.0f, 1.0f);
      h = 0.003f + 0.025f * std::pow(t, 1.25f);
      width = 0.0065f + 0.0050f * t * t;
    } else {
      const float u = (tip_y - y) / 0.015f;
      h = 0.028f * std::sqrt(std::max(0.0f, 1.0f - u * u));
      width = 0.0115f;
    }
    dz += h * smoothstep(0.070f, 0.060f, y) * gauss(xa / width);
    dz += 0.009f * gauss(std::hypot((xa - 0.0165f) / 0.0065f, (y - 0.012f) / 0.007f));
  }

  // Cheekbones, cheeks, the hollow under the eyes, the fold from nose wing to mouth corner.
  dz += 0.005f * gauss((xa - 0.046f) / 0.014f) * gauss((y - 0.037f) / 0.012f);
  dz += 0.004f * gauss((xa - 0.036f) / 0.016f) * gauss((y - 0.010f) / 0.015f);
  dz -= 0.002f * gauss((xa - 0.034f) / 0.012f) * gauss((y - 0.045f) / 0.006f);
  dz -= 0.0012f * gauss(segment_distance(xa, y, 0.020f, 0.013f, 0.031f, -0.010f) / 0.0025f);

  // Muzzle over the teeth, then the lips: vermilion bulges above and below the mouth line, fading
  // out at the corners. The upper lip's border has the two peaks of the Cupid's bow.
  dz += 0.006f * gauss(xa / 0.03f) * gauss((y - m.mouth_y) / 0.022f);
  const float w = m.mouth_half_width;
  // Full height over most of the width, rounding off smoothly into the corners (a steep cut-off
  // there would show as a crease at each end of the lips).
  const float across = smoothstep(w + 0.002f, w - 0.010f, xa) * (1.0f - 0.25f * (xa / w) * (xa / w));
  const float upper_h = 0.008f + 0.0012f * gauss((xa - 0.006f) / 0.004f) - 0.0008f * gauss(xa / 0.003f);
  const float upper = 0.0085f * across * gauss((-s / upper_h - 0.35f) / 0.55f);
  const float lower = 0.0085f * across * gauss((s / 0.012f - 0.45f) / 0.55f);
  const bool above = slit == kNotSlit ? s < 0.0f : slit < 0;
  if (slit == 0)
    dz += 0.5f * (upper + lower);
  else
    dz += above ? upper : lower;
  // The mouth-line rows fold into the mouth: deepest at the middle row, tapering to nothing at the
  // corners where the lips meet.
  if (slit != kNotSlit) {
    const float depth = m.mouth_depth * (1.0f - static_cast<float>(std::abs(slit)) / static_cast<float>(slit_rows + 1));
    dz -= depth * smoothstep(w, w - 0.007f, xa);
  }
  // The groove under the lower lip, and the chin.
  dz -= 0.0035f * gauss(xa / 0.02f) * gauss((s - 0.024f) / 0.006f);
  dz += 0.009f * gauss(xa / 0.017f) * gauss((y + 0.050f) / 0.012f);
  return dz;
}

}  // namespace

float below_mouth_line(const HeadLandmarks& m, float theta, float mouth_theta) {
  const float dy = m.mouth_y - m.centre.y, dz = 0.10f - m.centre.z;
  return (theta - mouth_theta) * std::sqrt(dy * dy + dz * dz);
}

glm::vec3 base_head_point(const HeadLandmarks& m, const HeadVertexParam& p) {
  const glm::vec3 d = direction(p.theta, p.phi);
  float r = smooth_max(cranium_extent(m, d), face_extent(m, d), 0.015f);
  r = smooth_max(r, neck_extent(m, d), 0.02f);
  glm::vec3 point = m.centre + r * d;
  // Ears: a radial bump on each side, just behind the jaw hinge.
  const float ear = gauss((point.y - 0.032f) / 0.02f) * gauss((point.z + 0.012f) / 0.011f) *
                    smoothstep(0.05f, 0.065f, std::abs(point.x));
  return point + 0.010f * ear * d;
}

void align_rows_to_eyelids(const HeadLandmarks& m, const HeadGrid& grid, std::span<glm::vec3> base) {
  const std::size_t rows = grid.rows();
  std::vector<float> v(rows), shift(rows);
  for (std::size_t c = 0; c < grid.columns(); ++c) {
    // The column's rows in the eye window, top to bottom (v decreasing).
    std::size_t first = rows, last = 0;
    for (std::size_t r = 0; r < rows; ++r) {
      const glm::vec3& p = base[grid.vertex(r, c)];
      const EyeCoords e = eye_coords(m, p.x, p.y);
      v[r] = e.v;
      if (p.z > 0.03f && std::abs(e.u) < 0.97f && e.v < upper_lid_edge(e.u) + 1.6f &&
          e.v > lower_lid_edge(e.u) - 1.2f) {
        first = std::min(first, r);
        last = std::max(last, r);
      }
    }
    if (first >= last) continue;
    // The row nearest each edge moves onto it, if it is within half a row spacing, and the next row
    // into the opening moves a fixed small step inside it, so the lid's rim is equally sharp all
    // along. Other rows shift by linear interpolation between these anchors and the window's ends
    // (which stay put), so row order never changes.
    auto nearest_row = [&](bool upper) -> std::size_t {
      std::size_t best = rows;
      float best_gap = 0.0f;
      for (std::size_t r = first; r <= last; ++r) {
        const EyeCoords e = eye_coords(m, base[grid.vertex(r, c)].x, base[grid.vertex(r, c)].y);
        const float gap = std::abs((upper ? upper_lid_edge(e.u) : lower_lid_edge(e.u)) - v[r]);
        if (best == rows || gap < best_gap) best = r, best_gap = gap;
      }
      if (best <= first + 1 || best + 1 >= last) return rows;
      return best_gap <= 0.25f * (v[best - 1] - v[best + 1]) ? best : rows;
    };
    constexpr float kRim = 0.1f;  // v units, about 0.7 mm
    std::vector<std::pair<std::size_t, float>> anchors{{first, 0.0f}};
    auto add_anchor = [&](std::size_t r, float target) {
      if (r > anchors.back().first && r < last) anchors.emplace_back(r, target - v[r]);
    };
    const std::size_t up = nearest_row(true), low = nearest_row(false);
    // Need at least one row strictly between the two rims to keep them apart.
    const bool both = up != rows && low != rows && low >= up + 3;
    if (up != rows && (both || low == rows)) {
      const EyeCoords e = eye_coords(m, base[grid.vertex(up, c)].x, base[grid.vertex(up, c)].y);
      add_anchor(up, upper_lid_edge(e.u));
      const EyeCoords f = eye_coords(m, base[grid.vertex(up + 1, c)].x, base[grid.vertex(up + 1, c)].y);
      add_anchor(up + 1, upper_lid_edge(f.u) - kRim);
    }
    if (low != rows && (both || up == rows)) {
      const EyeCoords f = eye_coords(m, base[grid.vertex(low - 1, c)].x, base[grid.vertex(low - 1, c)].y);
      add_anchor(low - 1, lower_lid_edge(f.u) + kRim);
      const EyeCoords e = eye_coords(m, base[grid.vertex(low, c)].x, base[grid.vertex(low, c)].y);
      add_anchor(low, lower_lid_edge(e.u));
    }
    anchors.emplace_back(last, 0.0f);
    for (std::size_t k = 0; k + 1 < anchors.size(); ++k) {
      const auto [r0, s0] = anchors[k];
      const auto [r1, s1] = anchors[k + 1];
      for (std::size_t r = r0; r <= r1; ++r) {
        const float t = r1 > r0 ? static_cast<float>(r - r0) / static_cast<float>(r1 - r0) : 0.0f;
        shift[r] = s0 + t * (s1 - s0);
      }
    }
    for (std::size_t r = first; r <= last; ++r) base[grid.vertex(r, c)].y += shift[r] * m.eye_half_height;
  }
}

glm::vec3 face_head_point(const HeadLandmarks& m, const HeadVertexParam& p, const glm::vec3& base, float mouth_theta,
                          int slit_rows) {
  glm::vec3 point = base;
  // The face is relief on the front only (z > 0.02): the same (x, y) at the back of the head is
  // untouched.
  const float front = smoothstep(0.02f, 0.05f, point.z);
  if (front <= 0.0f) return point;
  const float xa = std::abs(point.x);
  const float s = below_mouth_line(m, p.theta, mouth_theta);
  float z = point.z + face_relief(m, soft_abs(point.x), point.y, s, p.slit, slit_rows);

  // Eyes: within the opening the surface is the eyeball; around it the lid shell, blending into
  // brow and cheek further out.
  const EyeCoords e = eye_coords(m, point.x, point.y);
  if (eye_part(e.u, e.v) == EyePart::eyeball) {
    z = eyeball_front(m, xa, point.y);
  } else if (const float share = lid_share(m, e.u, e.v, xa, point.y); share > 0.0f) {
    z += share * (lid_front(m, xa, point.y) - z);
  }
  point.z += front * (z - point.z);
  return point;
}

}  // namespace performer::detail
