// Opening a glTF 2.0 file with tinygltf: binary (.glb) or JSON by its magic bytes rather than its
// name, images left undecoded (faces and skins need none, and an avatar's large or unsupported
// textures should neither cost time nor fail the load), and tinygltf's errors made one line.
// Shared by the face, skin and avatar readers, with the readers' parts that work on a model already
// opened, so that an avatar's skin and face come from one parse of the file. Private to the library.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include <tiny_gltf.h>

#include "performer/gltf_face.h"
#include "performer/skinned_mesh.h"

namespace performer::detail {

// Throws GltfError(file, ...) when the file cannot be opened or parsed.
tinygltf::Model load_gltf_model(const std::filesystem::path& path);

// The first node (in file order) with both a mesh and a skin; -1 when there is none.
int first_skinned_node(const tinygltf::Model& model);

// read_gltf_skinned's work on node `node_index` (which must have a mesh and a skin).
SkinnedMesh read_skinned_node(const tinygltf::Model& model, int node_index, const std::string& file);

// load_gltf_face's work on mesh `mesh_index` (which must have morph targets). With allow_no_match,
// a mesh with none of the targets the performer needs gives a face with no targets instead of the
// error, for callers to whom the face is optional (a skinned avatar still moves).
GltfFace read_gltf_face(const tinygltf::Model& model, std::size_t mesh_index, const VisemeSet& set,
                        const MorphMapping& mapping, const GltfFaceOptions& options, const std::string& file,
                        bool allow_no_match = false);

}  // namespace performer::detail
