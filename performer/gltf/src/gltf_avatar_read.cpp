#include <algorithm>
#include <string>

#include <tiny_gltf.h>

#include "gltf_load.h"
#include "performer/gltf_avatar.h"
#include "performer/gltf_skin.h"

namespace performer {

namespace {

bool has_morph_targets(const tinygltf::Mesh& mesh) {
  return std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                     [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
}

}  // namespace

GltfAvatar load_gltf_avatar(const std::filesystem::path& path, const VisemeSet& set, const MorphMapping& mapping) {
  const std::string file = path.string();
  const tinygltf::Model model = detail::load_gltf_model(path);
  GltfAvatar out;
  const int node = detail::first_skinned_node(model);
  if (node < 0) {
    const auto face_mesh = std::find_if(model.meshes.begin(), model.meshes.end(), has_morph_targets);
    if (face_mesh == model.meshes.end())
      throw GltfError(file,
                      "no skinned mesh and no morph targets: an avatar needs a mesh bound to a skin "
                      "(JOINTS_0, WEIGHTS_0 and a skin's joints) to follow the motion capture, or a face "
                      "with morph targets to put on the generated body");
    GltfFace face = detail::read_gltf_face(model, static_cast<std::size_t>(face_mesh - model.meshes.begin()), set,
                                           mapping, {}, file);
    out.face = std::move(face.model);
    out.mesh = std::move(face.mesh);
    out.missing = std::move(face.missing);
    return out;
  }

  out.skinned = true;
  out.skin = detail::read_skinned_node(model, node, file);
  const auto mesh_index = static_cast<std::size_t>(model.nodes[static_cast<std::size_t>(node)].mesh);
  const tinygltf::Mesh& mesh = model.meshes[mesh_index];
  out.mesh = mesh.name.empty() ? "mesh " + std::to_string(mesh_index) : mesh.name;
  if (!has_morph_targets(mesh)) {
    out.face.positions = out.skin.mesh.positions;
    out.face.normals = out.skin.mesh.normals;
    out.face.indices = out.skin.mesh.indices;
    return out;
  }
  // The skin reader accepted every primitive as triangles, so the face reader (which skips points and
  // lines) merges the same primitives in the same order: vertex v is the same vertex in both.
  GltfFace face = detail::read_gltf_face(model, mesh_index, set, mapping, {}, file, /*allow_no_match=*/true);
  if (face.model.vertex_count() != out.skin.mesh.positions.size())
    throw GltfError(file, "mesh '" + out.mesh + "': the face has " + std::to_string(face.model.vertex_count()) +
                              " vertices, the skin " + std::to_string(out.skin.mesh.positions.size()));
  // The face's neutral normals are the ones its normal DVs were made against (completed the same way
  // when the file leaves them out), so the skin takes them.
  out.skin.mesh.normals = face.model.normals;
  out.face = std::move(face.model);
  out.missing = std::move(face.missing);
  return out;
}

GltfAvatar load_gltf_avatar(const std::filesystem::path& path, const VisemeSet& set) {
  return load_gltf_avatar(path, set, load_morph_mapping(default_morph_dir()));
}

}  // namespace performer
