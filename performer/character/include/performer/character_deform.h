// Equation 3.20, per frame: the integrated facial and skeletal deformation of the whole character
// (thesis 3.6). The head's vertex range is first deformed by the face (equation 3.9 for positions,
// 3.11 for normals) in the rest pose, where the DVs were authored, then every vertex is skinned
// (equation 3.17 for positions, 3.19 for normals). Body vertices go straight from the rest streams to
// skinning; only the head range passes through the face step.
//
// The job holds views only; the caller owns the streams and the per-frame scratch (CharacterFrame
// sizes everything once), so a frame allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "performer/character.h"

namespace performer {

struct CharacterDeformJob {
  // Rest pose of the merged mesh (Character::mesh).
  std::span<const glm::vec3> rest_positions;
  std::span<const glm::vec3> rest_normals;  // empty to skip normals
  // The head range and its face streams (each DV stream head_count long, one weight per target).
  std::size_t head_first = 0;
  std::size_t head_count = 0;
  std::span<const std::span<const glm::vec3>> position_dvs;
  std::span<const std::span<const glm::vec3>> normal_dvs;  // same count, or empty when skipping normals
  std::span<const float> face_weights;
  // Skinning streams over all vertices and this frame's matrices (skinning_matrices()).
  int influences = 4;
  std::span<const glm::mat4> matrices;
  std::span<const std::uint16_t> joint_indices;
  std::span<const float> joint_weights;
  // Scratch, head_count long: the deformed head in the rest pose, between the two steps.
  std::span<glm::vec3> head_positions;
  std::span<glm::vec3> head_normals;  // empty exactly when rest_normals is
  // Output, all vertices; must not overlap any input or the scratch.
  std::span<glm::vec3> out_positions;
  std::span<glm::vec3> out_normals;  // empty exactly when rest_normals is

  // Sizes agree, the head range lies inside the mesh and every joint index names a matrix.
  bool valid() const;
};

// Equation 3.20 on one thread. Throws std::invalid_argument when !job.valid().
void deform_character(const CharacterDeformJob& job);

// The same on up to `threads` threads (0: hardware concurrency), bit for bit identical: each vertex
// is computed by the same arithmetic whichever thread runs it.
void deform_character_parallel(const CharacterDeformJob& job, unsigned threads = 0);

// Everything a frame of one character needs besides the character itself, sized once and reused:
// the DV span tables, the per-target weights, the skinning matrices and the scratch and output
// streams. Fill `weights` (target_weights()) and `matrices` (skinning_matrices()) each frame, then
// run job() through deform_character.
struct CharacterFrame {
  std::vector<std::span<const glm::vec3>> position_dvs;
  std::vector<std::span<const glm::vec3>> normal_dvs;
  std::vector<float> weights;       // one per target, all 0 to start with
  std::vector<glm::mat4> matrices;  // one per joint, identity to start with (the rest pose)
  std::vector<glm::vec3> head_positions, head_normals;
  std::vector<glm::vec3> positions, normals;  // the result

  // `character` must outlive the frame (the DV tables view its streams).
  explicit CharacterFrame(const Character& character);
  CharacterDeformJob job(const Character& character);
};

}  // namespace performer
