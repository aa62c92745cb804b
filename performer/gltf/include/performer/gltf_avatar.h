// A whole glTF 2.0 avatar for `performer render --gltf`: the skinned mesh (gltf_skin.h) whose morph
// targets, when it has any, are the face's deformation vectors (gltf_face.h), both read from one
// parse of the file so that the skin's and the face's vertices are the same vertices. An avatar with
// no skin but a face (a head exported by write_gltf_face, say) is returned as the face alone, for the
// caller to place on a body of its own.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "performer/face_model.h"
#include "performer/gltf_face.h"
#include "performer/morph_mapping.h"
#include "performer/skinned_mesh.h"
#include "performer/viseme_set.h"

namespace performer {

struct GltfAvatar {
  bool skinned = false;  // the file has a mesh bound to a skin; `skin` holds it
  // When skinned: the first node (in file order) with a mesh and a skin, in its bind pose, with the
  // face's neutral positions and normals (so that the DVs fit them exactly).
  SkinnedMesh skin;
  // When skinned: the same vertices and triangles, with the performer's targets made from the mesh's
  // morph targets (load_gltf_face's matching); no targets when the mesh has none the performer
  // needs. When not skinned: the first mesh with morph targets, as load_gltf_face reads it.
  FaceModel face;
  std::string mesh;                  // the mesh read (its name, or "mesh N" when unnamed)
  std::vector<std::string> missing;  // our target names the file could not supply
};

// Throws GltfError ("FILE: problem", one line) for an unreadable or malformed file, a file with
// neither a skinned mesh nor a mesh with morph targets, and as read_gltf_skinned and load_gltf_face
// do for the mesh they read (a skinless face must have some of the targets the performer needs).
GltfAvatar load_gltf_avatar(const std::filesystem::path& path, const VisemeSet& set, const MorphMapping& mapping);
// The same with load_morph_mapping(default_morph_dir()).
GltfAvatar load_gltf_avatar(const std::filesystem::path& path, const VisemeSet& set);

}  // namespace performer
