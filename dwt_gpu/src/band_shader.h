#pragma once
#include "dwt/band_operation.h"
#include "glcontext/gl_api.h"
#include "glcontext/resources.h"

namespace dwt_gpu {

// The wavelet-domain operation of thesis 4.7 as a fragment pass: drawn once per band, over the
// band's rectangle, it writes rule(first_factor * a, second_factor * b) of the two coefficient
// textures at the same texel (dwt::apply_rule, the CPU's formula).
struct BandShader {
  glc::Program program;
  GLint first = -1;          // sampler2D: the first plane's coefficients (R32F)
  GLint second = -1;         // sampler2D: the second plane's coefficients; only read by rules naming it
  GLint rule = -1;           // int: dwt::BandRule
  GLint first_factor = -1;   // float
  GLint second_factor = -1;  // float

  static BandShader build(const glc::GlApi& gl);
};

}  // namespace dwt_gpu
