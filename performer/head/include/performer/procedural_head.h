// A parametric head to animate when no artist-made face is at hand (thesis 3.4.1: "a set of faces
// with the same topology"): a closed, watertight mesh with a cranium, jaw and chin, cheeks, nose,
// lips meeting at a mouth line, eyes under lids, and brows, plus one deformation vector per viseme
// of the thesis set and per expression, each authored as a handful of parametric movements (jaw
// rotation, lip rounding, spreading, pressing, eyelid closing, ...) rather than sculpted.
//
// Coordinates (what an attachment to a skeleton needs): metres; the origin is the head's pivot on
// the spine, at the base of the skull where the skull sits on the top of the neck (the atlas joint,
// where a BVH "Head" joint is usually placed); +Y up, the face looking along +Z, +X to the head's
// own left. At scale 1 the chin is at y = -0.067 and the crown at y = +0.165 (chin to crown about
// 0.23 m); the eyes are centred at x = +-0.032, y = 0.060, the mouth line is at y = -0.012 and
// 0.05 m wide, the nose tip near z = +0.125; a short neck stub, closed at the bottom, reaches down
// to y = -0.11.
//
// The surface is a latitude-longitude grid around a point inside the head, pinched into two poles
// (crown and the bottom of the neck): closed and consistently oriented by construction. Rows and
// columns crowd onto the eyes and mouth so lids and lips have enough vertices; a few extra rows
// along the mouth line form the lips' inner surfaces, folded into the mouth when it is closed and
// unfolded into the mouth cavity when the jaw opens (the mesh never gets a hole).
#pragma once

#include <array>
#include <string_view>

#include "performer/face_model.h"
#include "performer/viseme_set.h"

namespace performer {

// The expression targets the procedural head carries besides the visemes (thesis Figure 3.11 and
// the eye-action channel of 3.4.5).
inline constexpr std::array<std::string_view, 5> kHeadExpressions = {"smile", "worry", "surprise", "anger", "blink"};

struct HeadParams {
  int rings = 78;      // latitude rows (the mouth line adds 2 * mouth_rows + 1 and takes a few)
  int segments = 112;  // longitude columns; even, so the head is mirror-symmetric about x = 0
  int mouth_rows = 3;  // rows on each side of the mouth line for the lips' inner surfaces, 1..8
  float focus = 1.0f;  // how strongly rows and columns crowd onto eyes and mouth: 0 uniform, up to 3
  float scale = 1.0f;  // uniform size factor for positions and deltas
};

// The neutral head and its targets: every viseme of `set` in ID order, each named like the viseme,
// then kHeadExpressions in order. Viseme shapes are chosen by the viseme's name when it is one of the
// thesis names (visemes.tsv), else by its Oculus viseme, so an edited set still gets sensible
// shapes. "closed" (Oculus "sil") is the neutral face itself, so its DV is zero, as equation 3.5
// makes it. Normal DVs are the deformed mesh's recomputed normals minus the neutral normals.
// Deterministic: the same parameters give the same mesh bit for bit. Throws std::invalid_argument
// for parameters out of range.
FaceModel build_procedural_head(const VisemeSet& set, const HeadParams& params = {});

}  // namespace performer
