#pragma once
#include <array>

#include "dwt/kernel.h"
#include "glcontext/gl_api.h"
#include "glcontext/resources.h"

namespace dwt_gpu {

// The vertex shader of every pass: one quad covering the viewport (drawn as a 4-vertex strip with no
// attributes), which each pass sets to the region it writes.
inline constexpr const char* kViewportQuadVertexShader = R"(#version 330 core
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr int kSelectors = 4;  // first kernel, second kernel, lone even sample, lone odd sample
constexpr int kTapsPerSelector = dwt::Kernel::kTaps;
using KernelBank = std::array<float, kSelectors * kTapsPerSelector>;

// The one fragment shader of the thesis' method, used for every pass: forward and inverse,
// horizontal and vertical, any kernel and boundary scheme (those arrive as uniforms and the table).
struct DwtShader {
  glc::Program program;
  GLint source = -1;    // sampler2D: the plane being transformed (R32F)
  GLint table = -1;     // sampler2D: the indirect address table (RGBA32F)
  GLint row = -1;       // int: table row of this level and axis
  GLint vertical = -1;  // int: 0 horizontal pass, 1 vertical pass
  GLint pad = -1;       // int: table texel of extended position 0
  GLint radius = -1;    // int: taps reach -radius..radius
  GLint taps = -1;      // float[36]: the kernel bank

  static DwtShader build(const glc::GlApi& gl);
};

// The bank a direction convolves with: analysis taps (forward) or interleaved synthesis taps
// (inverse), then the lone-sample rules as one-tap kernels: an even one passes, an odd one is
// doubled (forward) or halved (inverse).
KernelBank kernel_bank(const dwt::Kernel& kernel, bool inverse);

}  // namespace dwt_gpu
