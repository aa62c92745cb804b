// The procedural head's proportions and the eye geometry its shape and its poses share. Private to
// the library. Metres, origin at the head pivot, +Y up, +Z forward (procedural_head.h). The numbers
// are an average adult's, rounded: head 0.15 m wide and 0.21 m deep, eyes 64 mm apart, mouth 50 mm
// wide, chin to crown 0.23 m.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

namespace performer::detail {

struct HeadLandmarks {
  // The surface is a radial graph around this point: every vertex lies on a ray from it, so the
  // neutral mesh cannot fold over itself whatever the feature shapes.
  glm::vec3 centre{0.0f, 0.050f, 0.0f};

  // Cranium: an ellipsoid. Face and jaw: a tapered superellipsoid, boxier than an ellipsoid so the
  // chin stays forward under the mouth. Neck: a rounded cylinder (superquadric of revolution).
  glm::vec3 cranium_centre{0.0f, 0.065f, -0.008f};
  glm::vec3 cranium_axes{0.0760f, 0.100f, 0.100f};
  float cranium_power = 2.4f;
  glm::vec3 face_centre{0.0f, 0.008f, 0.004f};
  glm::vec3 face_axes{0.064f, 0.075f, 0.090f};
  float face_power = 3.0f;
  glm::vec3 neck_centre{0.0f, -0.025f, -0.018f};
  float neck_radius = 0.052f;
  float neck_half_height = 0.085f;  // bottom at y = -0.11

  // Eyes (the +X one; the other is mirrored). The lids are a shell shaped like the front of an
  // ellipsoid around the eye centre, wider than the eyeball so the corners of the opening sit
  // recessed as real ones do; the visible eyeball is that shell lid_thickness further back, with the
  // cornea bulging in the middle. The opening is an almond in the face plane measured in half widths
  // (u, across) and half heights (v, up).
  glm::vec3 eye{0.032f, 0.060f, 0.0735f};
  glm::vec3 eye_shell_axes{0.022f, 0.019f, 0.0145f};
  float lid_thickness = 0.0025f;
  float cornea_height = 0.0015f;
  float eye_half_width = 0.0145f;
  float eye_half_height = 0.0070f;

  // Mouth line and lips.
  float mouth_y = -0.012f;
  float mouth_half_width = 0.025f;
  float mouth_depth = 0.022f;                  // how far the lips' inner surfaces reach into the head
  float slit_step = 0.0025f;                   // angle (radians) between the mouth-line rows
  glm::vec3 jaw_hinge{0.0f, 0.030f, -0.012f};  // the jaw rotates about the x axis through this point
};

inline float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

inline float gauss(float x) { return std::exp(-x * x); }

// |x| and sign(x) rounded off within a few millimetres of the midline. Features are placed by
// distance from the midline; with the plain |x| any feature not flat there (a brow, a corner of the
// mouth) would put a crease down the middle of the face, and a sideways movement would tear the two
// halves apart.
inline float soft_abs(float x) { return std::sqrt(x * x + 0.002f * 0.002f); }
inline float soft_sign(float x) { return x / std::sqrt(x * x + 0.004f * 0.004f); }

// The eye opening's edges, in v units, at u (eye half widths from the centre, + toward the ear):
// the upper lid arches higher than the lower, and both tilt up toward the outer corner. At |u| >= 1
// both meet at the corner.
inline float upper_lid_edge(float u) {
  const float a = std::max(0.0f, 1.0f - u * u);
  return 0.95f * std::pow(a, 0.6f) + 0.10f * u;
}
inline float lower_lid_edge(float u) {
  const float a = std::max(0.0f, 1.0f - u * u);
  return -0.80f * std::pow(a, 0.8f) + 0.10f * u;
}

// The eye-opening coordinates of a face point (x mirrored onto the +X eye): u across in eye half
// widths (+ toward the ear), v up in eye half heights.
struct EyeCoords {
  float u = 0.0f;
  float v = 0.0f;
};
inline EyeCoords eye_coords(const HeadLandmarks& m, float x, float y) {
  return {(std::abs(x) - m.eye.x) / m.eye_half_width, (y - m.eye.y) / m.eye_half_height};
}

// How far (x, y) is from the eye centre relative to the lid shell's outline: 1 on the outline.
// xa = |x|, so both eyes use the +X one.
inline float eye_extent(const HeadLandmarks& m, float xa, float y) {
  const float dx = (xa - m.eye.x) / m.eye_shell_axes.x, dy = (y - m.eye.y) / m.eye_shell_axes.y;
  return std::sqrt(dx * dx + dy * dy);
}

// z of the lid shell's front at (|x|, y); the eye centre's z outside the outline, so differences
// between two such heights stay defined.
inline float lid_front(const HeadLandmarks& m, float xa, float y) {
  const float e = eye_extent(m, xa, y);
  return m.eye.z + m.eye_shell_axes.z * std::sqrt(std::max(0.0f, 1.0f - e * e));
}

// z of the visible eyeball at (|x|, y): under the lids by their thickness, the cornea in front of the
// iris.
inline float eyeball_front(const HeadLandmarks& m, float xa, float y) {
  const float r = std::hypot(xa - m.eye.x, y - m.eye.y);
  return lid_front(m, xa, y) - m.lid_thickness + m.cornea_height * gauss(r / 0.0055f);
}

// Vertices this close (in v units) to a lid edge count as on it: the neutral mesh puts a row of
// vertices exactly on each edge, up to rounding.
inline constexpr float kLidEdgeTolerance = 1e-3f;

// Which part of the eye region a face point is: the visible eyeball strictly inside the opening,
// otherwise upper or lower lid skin (or none of the eye, far away; callers weight by distance).
enum class EyePart { upper_lid, eyeball, lower_lid };
inline EyePart eye_part(float u, float v) {
  if (std::abs(u) < 1.0f && v > lower_lid_edge(u) + kLidEdgeTolerance && v < upper_lid_edge(u) - kLidEdgeTolerance)
    return EyePart::eyeball;
  return v >= upper_lid_edge(u) - kLidEdgeTolerance ? EyePart::upper_lid : EyePart::lower_lid;
}

// How much of a lid point's shape is the lid shell (1 at the edge of the opening, fading into brow
// and cheek, and gone before the shell's outline where the shell falls away).
inline float lid_share(const HeadLandmarks& m, float u, float v, float xa, float y) {
  const float upper = upper_lid_edge(u), lower = lower_lid_edge(u);
  const float outside = std::max({0.0f, v - upper, lower - v});
  const float dist = std::hypot(2.0f * std::max(0.0f, std::abs(u) - 1.0f), outside);
  const float fade = v > upper ? smoothstep(0.35f, 1.3f, dist) : smoothstep(0.25f, 0.9f, dist);
  return (1.0f - fade) * (1.0f - smoothstep(0.75f, 0.95f, eye_extent(m, xa, y)));
}

}  // namespace performer::detail
