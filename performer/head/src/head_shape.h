// The procedural head's neutral surface, built in three steps over the grid. Private to the library.
//   1. base_head_point: the skull, face, jaw and neck solids and the ears, one point per grid ray;
//   2. align_rows_to_eyelids: nudges vertices up or down within each column so that a row runs
//      exactly along each lid edge, which keeps the edges of the eye opening smooth instead of
//      stair-stepped across the grid;
//   3. face_head_point: the relief of the face (brows, nose, cheeks, lips, mouth line, chin) and the
//      eyes, as forward (z) offsets on the front of the head.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "head_grid.h"
#include "head_landmarks.h"

namespace performer::detail {

glm::vec3 base_head_point(const HeadLandmarks& marks, const HeadVertexParam& p);

// base: base_head_point of every grid vertex (HeadGrid vertex order); only y changes, by at most
// half a row spacing.
void align_rows_to_eyelids(const HeadLandmarks& marks, const HeadGrid& grid, std::span<glm::vec3> base);

// The finished neutral point. mouth_theta is HeadGrid::mouth_theta, slit_rows the K of the grid's
// mouth-line rows.
glm::vec3 face_head_point(const HeadLandmarks& marks, const HeadVertexParam& p, const glm::vec3& base,
                          float mouth_theta, int slit_rows);

// Signed distance below the mouth line, in metres along the face (negative above), measured as the
// latitude difference times the mouth's distance from the surface centre: exact on the mouth-line
// rows, which sit at the same (x, y) to within a fraction of a millimetre.
float below_mouth_line(const HeadLandmarks& marks, float theta, float mouth_theta);

}  // namespace performer::detail
