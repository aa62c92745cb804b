// The whole virtual performer as one mesh (thesis 3.6): the body grown around the skeleton
// (body_mesh.h) and a face model (face_model.h; the procedural head when no artist's face is at hand)
// placed on the skeleton's head joint, merged into one vertex and index stream and bound to the
// skeleton. What equation 3.20 needs per vertex is kept as plain streams, laid out as a vertex shader
// reads them: rest positions and normals, joint indices and weights, and, for the head's vertex range
// only, the face's deformation vectors already turned into the body's frame.
//
// Binding: body vertices get skeleton-aware SSD weights (body_weights.h: each vertex seeded by the
// bone it was grown from and that bone's skeleton neighbours, then blended by diffusion over the
// skin), which keep the skin in one piece in motion where equation 3.18's distance weights over all
// joints tear it (bind_body_to_skeleton). Head vertices are bound
// rigidly to the head joint (one influence, weight 1) by default. The thesis' argument for applying
// face deformation before skinning (3.6) is that head rotation and face deformation are orthogonal:
// the face's DVs are authored for a rigid head. SSD over the head would pull the chin and the neck
// stub towards the neck and shoulder joints, shearing the face the DVs were made for and bending the
// head's shape as the neck turns; a rigid head moves exactly as the head bone does. HeadBinding::ssd
// is kept for comparison.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "performer/body_mesh.h"
#include "performer/body_weights.h"
#include "performer/face_model.h"
#include "performer/skeleton.h"
#include "performer/ssd_weights.h"
#include "performer/triangle_mesh.h"

namespace performer {

enum class HeadBinding { rigid, ssd };

struct CharacterParams {
  // body.shape.exclude_from names the joint the head goes on ("Head" for CMU files); the head model
  // is taken to be in metres and placed with BodyMesh::head_placement.
  BodyMeshParams body;
  BodyWeightParams body_weights;  // the body's
  SsdWeightParams weights;        // equation 3.18, for the head when head = ssd
  HeadBinding head = HeadBinding::rigid;
  unsigned threads = 0;  // for building (body grid, weights); 0: hardware concurrency
};

struct Character {
  // Rest (neutral) pose in output units: body vertices first, then the head's, whose indices are
  // offset by the body's vertex count. Normals unit length.
  TriangleMesh mesh;
  std::size_t head_first = 0;  // the head's vertex range in mesh: [head_first, head_first + head_count)
  std::size_t head_count = 0;
  // Skinning streams over all vertices, indices naming skeleton joints (end sites included in the
  // numbering, never weighted), as SkinningJob consumes them.
  int influences = 4;
  std::vector<std::uint16_t> joint_indices;
  std::vector<float> joint_weights;
  // One per skeleton joint: rest world transform inverted, for skinning_matrices(). When
  // body.output_scale is not 1 these belong to the skeleton with its offsets (and position
  // channels) multiplied by output_scale; pose that skeleton.
  std::vector<glm::mat4> inverse_bind;
  int head_joint = -1;  // the joint the head is placed on
  // The face's targets in the face model's order (so bind_channels(track, face) indexes them), their
  // deltas covering the head range only and expressed in the body frame: position DVs by the
  // placement's linear part, normal DVs by its inverse-transpose, scaled per vertex like the neutral
  // normal so that neutral + DV is the transformed target normal up to length (equation 3.11
  // renormalises).
  std::vector<MorphTarget> targets;
  glm::mat4 head_placement{1.0f};  // face model coordinates -> output units

  std::size_t vertex_count() const { return mesh.positions.size(); }
};

// Builds the body around `skeleton`, places `face` on the joint named params.body.shape.exclude_from,
// merges and binds them. Throws std::invalid_argument when the skeleton has no such joint, the face
// model is invalid (validate_face_model), or as build_body_mesh and bind_to_skeleton do.
Character build_character(const Skeleton& skeleton, const FaceModel& face, const CharacterParams& params = {});

// The merged streams are consistent: sizes agree, indices in range and a multiple of 3, the head
// range inside the mesh, every DV stream head_count long, joint indices naming inverse_bind entries.
// Returns the first problem found, empty when there is none.
std::string character_problem(const Character& character);

}  // namespace performer
