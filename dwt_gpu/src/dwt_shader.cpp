#include "dwt_shader.h"

namespace dwt_gpu {
namespace {

// Equation 4.10 / 4.14: z(n) = sum_k f(n, k) * lambda'(n, k), with f chosen by the selector alpha
// and lambda' fetched through the table at base position beta. Everything position-dependent comes
// from the table, so this shader has no branches on boundaries, parity or direction.
constexpr const char* kFragmentShader = R"(#version 330 core
uniform sampler2D u_source;
uniform sampler2D u_table;
uniform int u_row;
uniform int u_vertical;
uniform int u_pad;
uniform int u_radius;
uniform float u_taps[36];
out float result;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int n = (u_vertical == 1) ? p.y : p.x;
  vec4 selector = texelFetch(u_table, ivec2(n + u_pad, u_row), 0);
  int alpha = int(selector.g);
  int beta = int(selector.b);
  float acc = 0.0;
  for (int t = -u_radius; t <= u_radius; ++t) {
    int address = int(texelFetch(u_table, ivec2(beta + t + u_pad, u_row), 0).r);
    ivec2 q = (u_vertical == 1) ? ivec2(p.x, address) : ivec2(address, p.y);
    float sample_value = (address >= 0) ? texelFetch(u_source, q, 0).r : 0.0;
    acc += u_taps[alpha * 9 + t + 4] * sample_value;
  }
  result = acc;
}
)";

static_assert(kTapsPerSelector == 9 && kSelectors * kTapsPerSelector == 36, "shader constants");

}  // namespace

DwtShader DwtShader::build(const glc::GlApi& gl) {
  DwtShader s;
  s.program = glc::Program::link(gl, kViewportQuadVertexShader, kFragmentShader, "dwt convolution");
  s.source = s.program.uniform("u_source");
  s.table = s.program.uniform("u_table");
  s.row = s.program.uniform("u_row");
  s.vertical = s.program.uniform("u_vertical");
  s.pad = s.program.uniform("u_pad");
  s.radius = s.program.uniform("u_radius");
  s.taps = s.program.uniform("u_taps");
  return s;
}

KernelBank kernel_bank(const dwt::Kernel& kernel, bool inverse) {
  KernelBank bank{};
  const auto& taps = inverse ? kernel.synthesis : kernel.analysis;
  for (int sel = 0; sel < 2; ++sel)
    for (int t = 0; t < kTapsPerSelector; ++t)
      bank[static_cast<std::size_t>(sel * kTapsPerSelector + t)] =
          static_cast<float>(taps[static_cast<std::size_t>(sel)][static_cast<std::size_t>(t)]);
  bank[2 * kTapsPerSelector + dwt::Kernel::kMaxRadius] = 1.0f;
  bank[3 * kTapsPerSelector + dwt::Kernel::kMaxRadius] = inverse ? 0.5f : 2.0f;
  return bank;
}

}  // namespace dwt_gpu
