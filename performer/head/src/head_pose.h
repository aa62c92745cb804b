// Parametric movements of the procedural head: how a viseme or an expression target is authored.
// Each field is one muscle-like movement at full strength 1 (or an angle); a target is a FacePose
// applied to the neutral mesh. Private to the library.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "head_grid.h"
#include "head_landmarks.h"

namespace performer::detail {

struct FacePose {
  float jaw_open = 0.0f;         // radians about the jaw hinge; the lower lip and chin follow
  float lip_round = 0.0f;        // corners drawn toward the middle, lips parted into an O
  float lip_protrude = 0.0f;     // lips pushed forward
  float lip_spread = 0.0f;       // corners drawn out and back, lips thinned
  float lip_press = 0.0f;        // lips rolled in and pressed together
  float lower_lip_tuck = 0.0f;   // lower lip up and back under the upper teeth (f, v)
  float upper_lip_raise = 0.0f;  // upper lip up, off the teeth
  float lower_lip_drop = 0.0f;   // lower lip down, off the teeth
  float tongue_out = 0.0f;       // the mouth floor pushed forward between the lips (th)
  float corner_up = 0.0f;        // mouth corners up (smile) or, negative, down
  float cheek_raise = 0.0f;      // cheeks pushed up and forward
  float brow_inner_up = 0.0f;    // inner ends of the brows up and together (worry)
  float brow_outer_up = 0.0f;    // outer ends of the brows up (surprise)
  float brow_down = 0.0f;        // brows lowered and drawn together (anger)
  float lid_close = 0.0f;        // upper lids: 1 closed, negative opened wider
  float lower_lid_up = 0.0f;     // lower lids raised (squint, smile)
};

// out[v] = neutral[v] moved by the pose. params from HeadGrid::vertex_params(); mouth_theta and
// slit_rows as for face_head_point. Sizes must agree (checked by the caller).
void pose_head(const HeadLandmarks& marks, std::span<const HeadVertexParam> params, float mouth_theta, int slit_rows,
               std::span<const glm::vec3> neutral, const FacePose& pose, std::span<glm::vec3> out);

}  // namespace performer::detail
