// A skin mesh generated for any skeleton (thesis 3.5.1: "a skeleton is embedded in, and attached
// to, a character model"): when no modelled character comes with the motion capture, the performer
// grows one around the skeleton's rest pose. The implicit body of body_shape.h is sampled on a grid,
// meshed by marching cubes, smoothed with Taubin's filter and given area-weighted normals. The
// result is in the rest pose, so it binds to the skeleton as it stands (ssd_weights.h) and is posed
// by skinning.h like any other mesh.
//
// The head is left to a separate model: bones from the joint named BodyShapeParams::exclude_from
// ("Head" for CMU files) are not grown, the neck stays full width up to that joint, and the joint's
// rest transform is reported for placing the head there.
#pragma once

#include <vector>

#include <glm/mat4x4.hpp>

#include "performer/body_shape.h"
#include "performer/mesh_smooth.h"
#include "performer/skeleton.h"
#include "performer/triangle_mesh.h"

namespace performer {

// Metres per unit of the CMU BVH files (cgspeed's conversion keeps the ASF lengths, which CMU states
// at 0.45 units per inch): hips stand 0.95 m above the floor, the figure about 1.6 m tall.
inline constexpr float kCmuMetersPerUnit = 0.0254f / 0.45f;

struct BodyMeshParams {
  BodyShapeParams shape;
  // Grid cells along the largest extent of the body. Vertex count grows with its square: 128 gives
  // about 15k vertices for a CMU skeleton.
  int grid_cells = 128;
  TaubinParams smoothing;
  // Only for placing parts modelled in metres (head_placement); the body itself is sized from the
  // skeleton.
  float meters_per_unit = kCmuMetersPerUnit;
  // Output positions are skeleton units times this: 1 to skin with the skeleton as read,
  // meters_per_unit for a mesh in metres (scale the skeleton's offsets alike before skinning).
  float output_scale = 1.0f;
  unsigned threads = 0;  // for grid sampling and smoothing; 0: hardware concurrency
};

struct BodyMesh {
  TriangleMesh mesh;                  // closed, outward-facing, unit normals, in output units
  BodyShape shape;                    // what it was grown from, in skeleton units
  float cell = 0.0f;                  // grid spacing used, in skeleton units
  float output_scale = 1.0f;          // mesh units per skeleton unit (BodyMeshParams::output_scale)
  int attach_joint = -1;              // the joint named shape.exclude_from, -1 if none
  glm::mat4 attach_rest_world{1.0f};  // that joint's rest world transform, translation in output units
  // Maps a head modelled in metres (neck base at the origin, +Y up, facing +Z) onto the attach joint
  // in output units: attach_rest_world times a uniform scale of output_scale / meters_per_unit.
  glm::mat4 head_placement{1.0f};
};

// Grows the body around the skeleton's rest pose (every channel zero). Throws std::invalid_argument
// for bad parameters or a skeleton with no bone of nonzero length.
BodyMesh build_body_mesh(const Skeleton& skeleton, const BodyMeshParams& params = {});

// Each joint's rest world position (column 3 of its rest world transform), in skeleton units.
std::vector<glm::vec3> rest_joint_positions(const Skeleton& skeleton);

}  // namespace performer
