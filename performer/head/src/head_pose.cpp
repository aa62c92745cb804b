#include "head_pose.h"

#include <algorithm>
#include <cmath>

#include "head_shape.h"

namespace performer::detail {

namespace {

// How much a point belongs with the lower jaw rather than the upper face, 0..1. Between the lips it
// is a clean step at the mouth line (the middle mouth-line row, the back of the mouth, goes half
// way); past the corners it widens into a smooth blend so the cheeks stretch instead of tearing.
float lowerness(const HeadLandmarks& m, float s, float xa, int slit) {
  const float w = m.mouth_half_width;
  const float band = 0.0015f + 0.5f * std::max(0.0f, xa - (w - 0.004f));
  if (slit == kNotSlit) return smoothstep(-band, band, s);
  if (slit == 0) return 0.5f;
  const float between_lips = smoothstep(w - 0.006f, w + 0.004f, xa);
  const float b = 1e-6f + between_lips * band;
  return smoothstep(-b, b, s);
}

// The eyelids: the upper lid's edge moves to U' (closing toward the lower edge, or opening wider),
// the lower lid's edge to L'. The lid skin between edge and brow (or cheek) stretches or bunches
// along the same vertical line, and the visible eyeball between the edges is squeezed into what is
// left of the opening and pushed back under the lids. Lid skin keeps its share of the lid shell's
// shape, so a closed lid covers the eye as a smooth shell.
glm::vec3 eyelid_offset(const HeadLandmarks& m, const glm::vec3& p, float close, float lower_up) {
  const EyeCoords e = eye_coords(m, p.x, p.y);
  const float upper = upper_lid_edge(e.u), lower = lower_lid_edge(e.u);
  const float opening = upper - lower;
  if (opening <= 0.0f) return glm::vec3(0.0f);
  float new_upper = close >= 0.0f ? upper + close * (lower - upper) : upper - close * 0.6f * opening;
  const float new_lower = lower + lower_up * 0.5f * opening;
  new_upper = std::max(new_upper, new_lower);
  constexpr float kUpperBand = 1.4f, kLowerBand = 0.9f;  // lid skin up to the brow, down to the cheek
  const float xa = std::abs(p.x);
  const EyePart part = eye_part(e.u, e.v);
  float v = e.v;
  if (part == EyePart::eyeball) {
    const float squeeze = std::max(0.04f, (new_upper - new_lower) / opening);
    v = new_lower + (e.v - lower) * squeeze;
    const float y = m.eye.y + v * m.eye_half_height;
    const float covered = std::clamp(1.0f - (new_upper - new_lower) / opening, 0.0f, 1.0f);
    return {0.0f, y - p.y, eyeball_front(m, xa, y) - 0.0015f * covered - p.z};
  }
  if (part == EyePart::upper_lid && e.v <= upper + kUpperBand)
    v = new_upper + (e.v - upper) * (upper + kUpperBand - new_upper) / kUpperBand;
  else if (part == EyePart::lower_lid && e.v >= lower - kLowerBand)
    v = new_lower - (lower - e.v) * (new_lower - (lower - kLowerBand)) / kLowerBand;
  else
    return glm::vec3(0.0f);
  const float y = m.eye.y + v * m.eye_half_height;
  const float share = lid_share(m, e.u, e.v, xa, p.y);
  return {0.0f, y - p.y, share * (lid_front(m, xa, y) - lid_front(m, xa, p.y))};
}

}  // namespace

void pose_head(const HeadLandmarks& m, std::span<const HeadVertexParam> params, float mouth_theta, int slit_rows,
               std::span<const glm::vec3> neutral, const FacePose& pose, std::span<glm::vec3> out) {
  const float w = m.mouth_half_width;
  const float ca = std::cos(pose.jaw_open), sa = std::sin(pose.jaw_open);
  for (std::size_t i = 0; i < neutral.size(); ++i) {
    const glm::vec3 p = neutral[i];
    const HeadVertexParam& prm = params[i];
    const float front = smoothstep(0.02f, 0.05f, p.z);
    const float xa = soft_abs(p.x), sx = soft_sign(p.x);
    const float s = below_mouth_line(m, prm.theta, mouth_theta);
    const float low = lowerness(m, s, xa, prm.slit);
    const float up = 1.0f - low;
    glm::vec3 d(0.0f);

    if (front > 0.0f) {
      const float across = std::max(0.0f, 1.0f - (xa / w) * (xa / w));
      // Rounding: the ring of the lips drawn in toward the middle and forward, parted into an O.
      const float ring = smoothstep(w + 0.02f, w - 0.005f, xa) * gauss(s / 0.014f) * front;
      d.x -= pose.lip_round * 0.40f * p.x * ring;
      d.z += pose.lip_round * 0.004f * ring;
      d.y += pose.lip_round * 0.0035f * (up - low) * across * gauss(s / 0.012f) * front;
      // Protrusion: the lips forward, slightly flared.
      const float lips = smoothstep(w + 0.015f, w - 0.005f, xa) * gauss(s / 0.011f) * front;
      d.z += pose.lip_protrude * 0.007f * lips;
      d.y += pose.lip_protrude * 0.0012f * (up - low) * lips;
      // Spreading: the corners out and back.
      const float corner = (xa < w ? std::pow(xa / w, 1.5f) : gauss((xa - w) / 0.015f)) * gauss(s / 0.015f) * front;
      d.x += pose.lip_spread * 0.006f * sx * corner;
      d.z -= pose.lip_spread * 0.003f * corner;
      d.y += pose.lip_spread * 0.0008f * corner;
      // Pressing: the red of the lips rolled in, the skin just above and below bulging.
      d.z -= pose.lip_press * 0.003f * across * gauss(s / 0.008f) * front;
      d.z += pose.lip_press * 0.0015f * across * (gauss((s + 0.014f) / 0.005f) + gauss((s - 0.016f) / 0.006f)) * front;
      // Lower lip tucked under the upper teeth: back, and up away from the mouth line only (the
      // rows at the line stay put so the lips never pass through each other).
      const float lower_lip = low * smoothstep(w + 0.008f, w - 0.006f, xa) * gauss((s - 0.004f) / 0.009f) * front;
      d.z -= pose.lower_lip_tuck * 0.0055f * lower_lip;
      d.y += pose.lower_lip_tuck * 0.0015f * smoothstep(0.0f, 0.004f, s) * lower_lip;
      // Upper lip raised, lower lip dropped: the lips part at the line.
      const float lip_width = smoothstep(w + 0.01f, w - 0.006f, xa) * front;
      d.y += pose.upper_lip_raise * 0.003f * up * gauss((s + 0.004f) / 0.010f) * lip_width;
      d.z += pose.upper_lip_raise * 0.0008f * up * gauss((s + 0.004f) / 0.010f) * lip_width;
      d.y -= pose.lower_lip_drop * 0.003f * low * gauss((s - 0.005f) / 0.011f) * lip_width;
      d.z += pose.lower_lip_drop * 0.0008f * low * gauss((s - 0.005f) / 0.011f) * lip_width;
      // Tongue: the folded-in mouth-line rows pushed back out toward the lips in the middle.
      if (prm.slit != kNotSlit) {
        const float depth =
            m.mouth_depth * (1.0f - std::abs(static_cast<float>(prm.slit)) / static_cast<float>(slit_rows + 1));
        d.z += pose.tongue_out * 0.85f * std::max(0.0f, depth) * smoothstep(w, w - 0.007f, xa) * gauss(xa / 0.013f);
      }
      // Mouth corners up (out and back with it) or down.
      const float corners = (xa < w ? (xa / w) * (xa / w) : gauss((xa - w) / 0.012f)) * gauss(s / 0.012f) * front;
      d.y += pose.corner_up * 0.0075f * corners;
      d.x += std::abs(pose.corner_up) * (pose.corner_up > 0.0f ? 0.0035f : 0.001f) * sx * corners;
      d.z -= std::abs(pose.corner_up) * 0.002f * corners;
      // Cheeks.
      const float cheek = gauss((xa - 0.038f) / 0.014f) * gauss((p.y - 0.022f) / 0.014f) * front;
      d.y += pose.cheek_raise * 0.003f * cheek;
      d.z += pose.cheek_raise * 0.0025f * cheek;
      // Brows, and the forehead above them less and less.
      const float brow_band = smoothstep(0.060f, 0.074f, p.y) * (1.0f - smoothstep(0.09f, 0.125f, p.y)) * front;
      const float inner = gauss((xa - 0.012f) / 0.013f) * brow_band;
      d.y += pose.brow_inner_up * 0.006f * inner;
      d.x -= pose.brow_inner_up * 0.0015f * sx * inner;
      d.y += pose.brow_outer_up * 0.006f * gauss((xa - 0.045f) / 0.014f) * brow_band;
      d.y -= pose.brow_down * 0.0045f * gauss((xa - 0.02f) / 0.02f) * brow_band;
      d.x -= pose.brow_down * 0.0025f * sx * gauss((xa - 0.015f) / 0.015f) * brow_band;
      d.z += pose.brow_down * 0.0015f * gauss((xa - 0.01f) / 0.012f) * brow_band;
      // Eyelids (skipped when idle: the remapping is the identity only up to rounding).
      if (pose.lid_close != 0.0f || pose.lower_lid_up != 0.0f)
        d += front * eyelid_offset(m, p, pose.lid_close, pose.lower_lid_up);
    }

    glm::vec3 q = p + d;
    // The jaw: rotation about the hinge's x axis, blended by how much the point belongs to the jaw,
    // which ends behind the jaw angle and above the throat.
    if (pose.jaw_open != 0.0f) {
      // The lower lip does not follow the jaw evenly: its middle drops with the chin while its ends
      // stay tied to the corners, so the mouth opens into an oval rather than a slot.
      const float lip_zone = gauss(s / 0.012f) * smoothstep(w + 0.012f, w - 0.004f, xa);
      const float across = std::max(0.0f, 1.0f - (xa / w) * (xa / w));
      const float follow = 1.0f - lip_zone * (1.0f - std::sqrt(across));
      const float jaw = low * follow * smoothstep(-0.035f, -0.008f, p.z) * smoothstep(-0.10f, -0.072f, p.y);
      if (jaw > 0.0f) {
        const glm::vec3 r = q - m.jaw_hinge;
        const glm::vec3 turned = m.jaw_hinge + glm::vec3(r.x, r.y * ca - r.z * sa, r.y * sa + r.z * ca);
        q += jaw * (turned - q);
      }
    }
    out[i] = q;
  }
}

}  // namespace performer::detail
