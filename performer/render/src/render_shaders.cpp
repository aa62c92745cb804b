#include "render_shaders.h"

namespace performer::render::shaders {

// The deformed character from the deformer's output (position, normal), pushed out along the
// normal by u_push for the outline and the hair shells. a_hair: the head's rest position in the
// head model's frame (metres, +Y up, facing +Z) and the hair density there; 0 on the body.
const char* const kCharacterVertex = R"GLSL(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_hair;
uniform mat4 u_view_projection;
uniform float u_push;
uniform int u_head_first;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_hair;
flat out int v_head;
void main() {
  vec3 p = a_position + a_normal * u_push;
  v_world = p;
  v_normal = a_normal;
  v_hair = a_hair;
  v_head = gl_VertexID >= u_head_first ? 1 : 0;
  gl_Position = u_view_projection * vec4(p, 1.0);
}
)GLSL";

// Per-pixel Blinn-Phong under a key light and a sky/ground hemisphere; procedural materials (skin
// on the head, cloth on the body). With the environment on, a Fresnel rim reflects the cube map;
// in cartoon mode the light is quantised into three bands and one highlight.
const char* const kCharacterFragment = R"GLSL(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec4 v_hair;
flat in int v_head;
uniform vec3 u_eye;
uniform vec3 u_light;
uniform bool u_toon;
uniform bool u_environment;
uniform samplerCube u_cubemap;
out vec4 o_color;
void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(u_eye - v_world);
  vec3 l = normalize(u_light);
  bool skin = v_head == 1;
  vec3 base = skin ? vec3(0.86, 0.66, 0.55) : vec3(0.22, 0.33, 0.58);
  float diffuse = max(dot(n, l), 0.0);
  float specular = pow(max(dot(n, normalize(l + v)), 0.0), skin ? 24.0 : 60.0) * (skin ? 0.18 : 0.35);
  vec3 ambient = mix(vec3(0.16, 0.14, 0.12), vec3(0.32, 0.36, 0.44), 0.5 + 0.5 * n.y);
  if (u_toon) {
    diffuse = diffuse > 0.55 ? 1.0 : (diffuse > 0.2 ? 0.6 : 0.25);
    specular = specular > 0.12 ? 0.5 : 0.0;
    ambient = vec3(0.22);
  }
  vec3 color = base * (ambient + 0.85 * diffuse) + vec3(specular);
  if (u_environment && !u_toon) {
    float fresnel = pow(1.0 - max(dot(n, v), 0.0), 3.0);
    color += (skin ? 0.15 : 0.35) * fresnel * texture(u_cubemap, reflect(-v, n)).rgb;
  }
  o_color = vec4(color, 1.0);
}
)GLSL";

const char* const kOutlineFragment = R"GLSL(#version 330 core
out vec4 o_color;
void main() { o_color = vec4(0.04, 0.03, 0.03, 1.0); }
)GLSL";

// One hair shell: strands are cells of the scalp (u_strands per metre), each with a random length;
// a shell at height u_layer (0 at the scalp, 1 at the longest strand's tip) shows the strands that
// reach it, thinning towards the tips.
const char* const kHairFragment = R"GLSL(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec4 v_hair;
uniform vec3 u_light;
uniform float u_layer;
uniform float u_strands;
out vec4 o_color;
float hash(vec3 p) {
  p = fract(p * 0.3183099 + vec3(0.71, 0.113, 0.419));
  p *= 17.0;
  return fract(p.x * p.y * p.z * (p.x + p.y + p.z));
}
void main() {
  float density = v_hair.w;
  if (density <= 0.0) discard;
  float strand = hash(floor(v_hair.xyz * u_strands));
  float reach = 0.35 + 0.65 * strand;
  if (reach < u_layer) discard;
  vec3 n = normalize(v_normal);
  float light = 0.35 + 0.65 * max(dot(n, normalize(u_light)), 0.0);
  vec3 color = vec3(0.20, 0.12, 0.07) * (0.7 + 0.6 * u_layer) * light;
  o_color = vec4(color, density * (1.0 - 0.5 * u_layer));
}
)GLSL";

// A full-screen triangle on the far plane: the environment sphere, shaded from the cube map by the
// world-space view vector, or a plain sky gradient without the effect.
const char* const kSkyVertex = R"GLSL(#version 330 core
out vec2 v_ndc;
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  v_ndc = corner;
  gl_Position = vec4(corner, 1.0, 1.0);
}
)GLSL";

const char* const kSkyFragment = R"GLSL(#version 330 core
in vec2 v_ndc;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform bool u_environment;
uniform samplerCube u_cubemap;
out vec4 o_color;
void main() {
  vec4 far = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
  vec3 ray = normalize(far.xyz / far.w - u_eye);
  if (u_environment) {
    o_color = vec4(texture(u_cubemap, ray).rgb, 1.0);
  } else {
    float up = clamp(ray.y * 0.5 + 0.5, 0.0, 1.0);
    o_color = vec4(mix(vec3(0.55, 0.55, 0.58), vec3(0.32, 0.45, 0.68), up), 1.0);
  }
}
)GLSL";

// The floor: a large square at the character's feet with a soft checker, fading with distance.
const char* const kFloorVertex = R"GLSL(#version 330 core
layout(location = 0) in vec2 a_corner;
uniform mat4 u_view_projection;
uniform vec3 u_centre;
uniform float u_extent;
out vec3 v_world;
void main() {
  v_world = u_centre + vec3(a_corner.x * u_extent, 0.0, a_corner.y * u_extent);
  gl_Position = u_view_projection * vec4(v_world, 1.0);
}
)GLSL";

const char* const kFloorFragment = R"GLSL(#version 330 core
in vec3 v_world;
uniform vec3 u_centre;
uniform float u_extent;
uniform float u_tile;
uniform bool u_environment;
uniform bool u_toon;
out vec4 o_color;
void main() {
  vec2 cell = floor(v_world.xz / u_tile);
  float checker = mod(cell.x + cell.y, 2.0);
  vec3 a = u_environment ? vec3(0.42, 0.40, 0.36) : vec3(0.50, 0.50, 0.50);
  vec3 b = u_environment ? vec3(0.36, 0.34, 0.30) : vec3(0.42, 0.42, 0.43);
  vec3 color = mix(a, b, checker);
  if (u_toon) color = mix(vec3(0.8, 0.78, 0.7), vec3(0.72, 0.7, 0.62), checker);
  float fade = clamp(length(v_world.xz - u_centre.xz) / u_extent, 0.0, 1.0);
  o_color = vec4(color, 1.0 - fade * fade);
}
)GLSL";

// Snow: each flake a camera-facing square (two triangles of a strip) around its centre.
const char* const kSnowVertex = R"GLSL(#version 330 core
layout(location = 0) in vec4 a_flake;  // centre, size
uniform mat4 u_view_projection;
uniform vec3 u_right;
uniform vec3 u_up;
out vec2 v_corner;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1) * 2.0 - 1.0;
  v_corner = corner;
  vec3 p = a_flake.xyz + (u_right * corner.x + u_up * corner.y) * a_flake.w;
  gl_Position = u_view_projection * vec4(p, 1.0);
}
)GLSL";

const char* const kSnowFragment = R"GLSL(#version 330 core
in vec2 v_corner;
out vec4 o_color;
void main() {
  float r = dot(v_corner, v_corner);
  if (r > 1.0) discard;
  o_color = vec4(0.97, 0.98, 1.0, 0.9 * (1.0 - r));
}
)GLSL";

}  // namespace performer::render::shaders
