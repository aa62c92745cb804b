// Avatar faces from glTF 2.0 files (.gltf or .glb): a mesh with morph targets becomes a FaceModel
// whose targets are the performer's (thesis visemes by name, expressions, blink), matched from the
// rig's own names through the Oculus viseme and ARKit conventions in performer/data/morphs
// (morph_mapping.h). glTF morph targets are stored as displacements, which is exactly the
// deformation vector of equation 3.5, so they are taken over unchanged. The writer exports a
// FaceModel with morph targets named by our names, for viewers and engines and for test fixtures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "performer/face_model.h"
#include "performer/morph_mapping.h"
#include "performer/viseme_set.h"

namespace performer {

struct GltfFaceOptions {
  std::string mesh;          // mesh name; empty: the first mesh (in file order) with morph targets
  bool require_all = false;  // throw when any viseme or expression target is missing
};

struct GltfFace {
  FaceModel model;                   // targets: visemes in set order, then kHeadExpressions, then any
                                     // other expression arkit.tsv defines, as found
  std::string mesh;                  // the mesh read (its name, or "mesh N" when unnamed)
  std::vector<std::string> sources;  // per target: the morphs it was made from, e.g. "viseme_aa" or
                                     // "1*eyeBlinkLeft + 1*eyeBlinkRight"
  std::vector<std::string> missing;  // our target names the file could not supply
};

// Reads the mesh (all triangle primitives merged, in mesh space: node transforms are not applied;
// skinning places the face) and its morph targets, named by mesh.extras.targetNames (the common
// convention; a primitive's extras are used when the mesh has none). Every accessor layout tinygltf
// reads is accepted: any component type, normalised integers, strides, sparse accessors. Normals
// and normal deltas missing from the file are computed from the geometry.
// Each target of ours, for viseme V (Oculus viseme O) or expression E, is the first of:
//   1. a morph named V (or E) itself;
//   2. for a viseme, a morph with one of O's names in oculus.tsv (viseme_aa, viseme_I, ...);
//   3. a recipe in arkit.tsv for E, or for one of O's names, from whichever ingredients exist.
// The viseme mapped to Oculus "sil" is the neutral face by definition (equation 3.5), so it gets a
// zero DV when the file has no morph for it.
// Throws GltfError ("FILE: problem", one line) for an unreadable or malformed file, no mesh with
// morph targets (or no mesh of the given name), unnamed morph targets, bad accessors, and a mesh
// with none of the morph targets we need (naming what is missing and what the file has); with
// require_all, also when any target is missing. VisemeDataError for a malformed mapping file.
GltfFace load_gltf_face(const std::filesystem::path& path, const VisemeSet& set, const MorphMapping& mapping,
                        const GltfFaceOptions& options = {});
// The same with load_morph_mapping(default_morph_dir()).
GltfFace load_gltf_face(const std::filesystem::path& path, const VisemeSet& set, const GltfFaceOptions& options = {});

// Writes the model as one mesh with one primitive (float positions and normals, 32-bit indices)
// and one morph target per FaceModel target (POSITION and NORMAL displacements), their names in
// mesh.extras.targetNames and default weights 0. Binary when the path ends in .glb (any case),
// otherwise JSON with the buffer embedded as a data URI. Atomic: the file is complete or untouched.
// Throws std::invalid_argument when validate_face_model() does, GltfError when tinygltf cannot
// serialise the model, std::runtime_error ("FILE: problem") when the file cannot be written.
void write_gltf_face(const std::filesystem::path& path, const FaceModel& model);

}  // namespace performer
