#include "deform_shader.h"

namespace performer::render {

// Written to do what the CPU jobs do, step by step and in the same order, so that the two agree to
// rounding: face_deform.cpp's blend (base plus each acting DV times its weight, in target order;
// normals renormalised when any DV acts) and skinning.cpp's (blend the matrices of the nonzero
// weights, transform the point once; normals by the cofactor matrix, sign by the determinant).
std::string deform_vertex_shader(std::size_t joints, bool bones_in_texture, int face_slots) {
  const std::string slots = std::to_string(face_slots);
  std::string s = "#version 330 core\n";
  s += "#define FACE_SLOTS " + slots + "\n";
  s += "#define JOINTS " + std::to_string(joints == 0 ? 1 : joints) + "\n";
  if (bones_in_texture) s += "#define BONES_IN_TEXTURE 1\n";
  s += "#define POSITION_DVS " + std::to_string(kFirstPositionDvAttribute) + "\n";
  s += "#define NORMAL_DVS " + std::to_string(kFirstPositionDvAttribute + static_cast<unsigned>(face_slots)) + "\n";
  s += R"GLSL(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in uvec4 a_joints;
layout(location = 3) in vec4 a_weights;
layout(location = POSITION_DVS) in vec3 a_dv_position[FACE_SLOTS];
layout(location = NORMAL_DVS) in vec3 a_dv_normal[FACE_SLOTS];

#ifdef BONES_IN_TEXTURE
uniform samplerBuffer u_bone_texels;  // four RGBA32F texels (the columns) per matrix
mat4 bone(uint j) {
  int b = int(j) * 4;
  return mat4(texelFetch(u_bone_texels, b), texelFetch(u_bone_texels, b + 1), texelFetch(u_bone_texels, b + 2),
              texelFetch(u_bone_texels, b + 3));
}
#else
layout(std140) uniform Bones { mat4 u_bones[JOINTS]; };
mat4 bone(uint j) { return u_bones[j]; }
#endif

uniform float u_face_weights[FACE_SLOTS];  // 0 for an unused slot
uniform bool u_face_acting;                // any face weight of the frame nonzero (head draw only)

out vec3 v_position;
out vec3 v_normal;

void main() {
  // Equations 3.9 and 3.11: the face in the rest pose.
  vec3 p = a_position;
  vec3 n = a_normal;
  if (u_face_acting) {
    for (int s = 0; s < FACE_SLOTS; ++s) {
      float w = u_face_weights[s];
      if (w != 0.0) {
        p += w * a_dv_position[s];
        n += w * a_dv_normal[s];
      }
    }
    float len = length(n);
    n = len > 1e-12 ? n / len : a_normal;
  }
  // Equations 3.17 and 3.19: the blended bone matrix, then one transform.
  mat4 blended = mat4(0.0);
  for (int i = 0; i < 4; ++i) {
    float w = a_weights[i];
    if (w != 0.0) blended += w * bone(a_joints[i]);
  }
  vec3 a0 = blended[0].xyz, a1 = blended[1].xyz, a2 = blended[2].xyz;
  v_position = a0 * p.x + a1 * p.y + a2 * p.z + blended[3].xyz;
  vec3 c0 = cross(a1, a2), c1 = cross(a2, a0), c2 = cross(a0, a1);
  vec3 o = c0 * n.x + c1 * n.y + c2 * n.z;
  if (dot(a0, c0) < 0.0) o = -o;
  float len = length(o);
  v_normal = len > 1e-20 ? o / len : n;
  gl_Position = vec4(v_position, 1.0);
}
)GLSL";
  return s;
}

}  // namespace performer::render
