// A face as the thesis animates it (3.4.1, equations 3.5 and 3.6; normals 3.11): a neutral mesh,
// the closed-mouth expressionless face that is the origin of the face space, plus named deformation
// vectors. A deformation vector (DV) is stored as the per-vertex difference target - neutral, for
// positions (equation 3.5) and for normals (the "normal DVs" of 3.11), so blending never needs the
// target meshes themselves, only these streams: what the vertex shader of 3.4.5 reads.
//
// Every target shares the neutral mesh's topology (one delta per neutral vertex), as the face set of
// equation 3.2 requires.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace performer {

struct MorphTarget {
  std::string name;                        // a viseme name, an expression name, or "blink"
  std::vector<glm::vec3> position_deltas;  // DV, equation 3.5: target - neutral, one per vertex
  std::vector<glm::vec3> normal_deltas;    // normal DV, equation 3.11: target normal - neutral normal
};

struct FaceModel {
  std::vector<glm::vec3> positions;    // neutral face, metres
  std::vector<glm::vec3> normals;      // unit, one per vertex
  std::vector<std::uint32_t> indices;  // triangles, three per triangle, counter-clockwise from outside
  std::vector<MorphTarget> targets;    // names unique

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  // Index into targets of the target with this name; -1 when there is none.
  int find_target(std::string_view name) const;
  // The target with this name, or nullptr.
  const MorphTarget* target(std::string_view name) const;
};

// Checks that a model can be drawn and blended: normals and every delta stream sized like the
// positions, index count a multiple of 3, every index names a vertex, target names non-empty and
// unique, all values finite. Throws std::invalid_argument "WHAT: problem" (what: a file name or
// other label for the message).
void validate_face_model(const FaceModel& model, std::string_view what);

}  // namespace performer
