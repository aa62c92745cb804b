// Skinned meshes in glTF 2.0 files (.gltf with embedded or external buffers, or binary .glb), read
// with tinygltf: the mesh, its skin's joint hierarchy and inverse bind matrices, and the per-vertex
// JOINTS_n / WEIGHTS_n, into a SkinnedMesh (skinned_mesh.h) that feeds SkinningJob unchanged. The
// writer exports one, so generated characters (body_mesh.h) open in any glTF viewer and tests make
// their fixtures without downloaded assets.
#pragma once

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>

#include "performer/face_model.h"
#include "performer/skinned_mesh.h"

namespace performer {

// An unreadable, malformed or unsupported file. what() is "FILE: problem", on one line.
class GltfError : public std::runtime_error {
 public:
  GltfError(std::string file, std::string problem);
  const std::string& file() const { return file_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  std::string problem_;
};

// Reads the first node (in file order) that has both a mesh and a skin. All of the mesh's
// primitives are merged into one mesh; triangle lists, strips and fans are accepted, points and
// lines are not. Per primitive: POSITION, JOINTS_0 and WEIGHTS_0 are required, JOINTS_1/WEIGHTS_1
// are used when every primitive has them (8 influences), NORMAL is used when every primitive has
// it (otherwise normals are computed, area-weighted). Every component type the specification
// allows is read (float, normalised unsigned byte and short weights; unsigned byte and short joint
// indices; unsigned byte, short and int vertex indices), strided and sparse accessors included.
// Weights are normalised to sum 1 per vertex. Joints keep the skin's order; a joint's parent is its
// nearest ancestor node that is a joint. Missing inverseBindMatrices mean identities, as the
// specification says.
// Throws GltfError naming the file for: unreadable or malformed files, no skinned mesh node, a
// missing attribute, accessors of the wrong type or outside their buffers, vertex or joint indices
// out of range, negative weights or a vertex whose weights sum to zero.
SkinnedMesh read_gltf_skinned(const std::filesystem::path& path);

// Writes `skinned` as glTF 2.0: binary when the path ends in .glb, otherwise JSON with the buffer
// embedded as a data URI (one self-contained file). Joints become nodes (a non-identity `above`
// becomes a node of its own between joint and parent), the mesh one primitive on one more node,
// with JOINTS_n as unsigned shorts and WEIGHTS_n as floats, 4 slots per set (padded with zero
// weights). `morph_targets`, when given, become the mesh's morph targets (POSITION and NORMAL
// displacements over every vertex, named in mesh.extras.targetNames as write_gltf_face names them), so
// that one file carries a skinned avatar and its face. Throws std::invalid_argument when
// skinned_mesh_problem() finds one or a target does not cover every vertex, GltfError when the file
// cannot be written. Atomic: the file is complete or untouched.
void write_gltf_skinned(const std::filesystem::path& path, const SkinnedMesh& skinned,
                        std::span<const MorphTarget> morph_targets = {});

}  // namespace performer
