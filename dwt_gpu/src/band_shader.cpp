#include "band_shader.h"

#include "dwt_shader.h"

namespace dwt_gpu {
namespace {

// Rule numbers follow dwt::BandRule (static_asserts below). The second texture is fetched only
// when the rule reads it, so a pass over one plane needs no second texture.
constexpr const char* kBandFragmentShader = R"(#version 330 core
uniform sampler2D u_first;
uniform sampler2D u_second;
uniform int u_rule;
uniform float u_first_factor;
uniform float u_second_factor;
out float result;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float a = u_first_factor * texelFetch(u_first, p, 0).r;
  if (u_rule == 0) {
    result = a;
    return;
  }
  float b = u_second_factor * texelFetch(u_second, p, 0).r;
  if (u_rule == 1) result = b;
  else if (u_rule == 2) result = a + b;
  else result = abs(b) > abs(a) ? b : a;
}
)";

static_assert(static_cast<int>(dwt::BandRule::First) == 0 && static_cast<int>(dwt::BandRule::Second) == 1 &&
                  static_cast<int>(dwt::BandRule::Sum) == 2 && static_cast<int>(dwt::BandRule::LargerMagnitude) == 3,
              "the shader numbers the rules as dwt::BandRule does");

}  // namespace

BandShader BandShader::build(const glc::GlApi& gl) {
  BandShader s;
  s.program = glc::Program::link(gl, kViewportQuadVertexShader, kBandFragmentShader, "wavelet band operation");
  s.first = s.program.uniform("u_first");
  s.second = s.program.uniform("u_second");
  s.rule = s.program.uniform("u_rule");
  s.first_factor = s.program.uniform("u_first_factor");
  s.second_factor = s.program.uniform("u_second_factor");
  return s;
}

}  // namespace dwt_gpu
