#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "performer/detail/atomic_file.h"
#include "gltf_buffer_view.h"
#include "performer/gltf_face.h"
#include "performer/gltf_skin.h"

namespace performer {

namespace {

// Builds the single buffer, its views and accessors as data is appended.
class GltfBuilder {
 public:
  explicit GltfBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  // A VEC3 float accessor over `data`, with the min/max glTF requires for POSITION attributes
  // (morph targets' included).
  int vec3(const std::vector<glm::vec3>& data, bool bounds) {
    const int view = append(data.data(), data.size() * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = data.size();
    if (bounds) {
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
      for (const glm::vec3& v : data) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
      a.minValues = {lo.x, lo.y, lo.z};
      a.maxValues = {hi.x, hi.y, hi.z};
    }
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  int indices(const std::vector<std::uint32_t>& data) {
    const int view = append(data.data(), data.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = data.size();
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

 private:
  int append(const void* bytes, std::size_t size, int target) {
    return detail::append_buffer_view(model_, bytes, size, target);
  }

  tinygltf::Model& model_;
};

bool is_glb(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".glb";
}

}  // namespace

void write_gltf_face(const std::filesystem::path& path, const FaceModel& face) {
  const std::string file = path.string();
  validate_face_model(face, file);
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "gpuj2k performer";
  GltfBuilder build(model);

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = build.vec3(face.positions, true);
  prim.attributes["NORMAL"] = build.vec3(face.normals, false);
  prim.indices = build.indices(face.indices);
  tinygltf::Value::Array names;
  for (const MorphTarget& t : face.targets) {
    prim.targets.push_back(
        {{"POSITION", build.vec3(t.position_deltas, true)}, {"NORMAL", build.vec3(t.normal_deltas, false)}});
    names.emplace_back(t.name);
  }
  tinygltf::Mesh mesh;
  mesh.name = "face";
  mesh.primitives.push_back(prim);
  if (!face.targets.empty()) {
    mesh.weights.assign(face.targets.size(), 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(std::move(names));
    mesh.extras = tinygltf::Value(std::move(extras));
  }
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "face";
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // Serialised in memory (buffer embedded: a data URI in JSON, the BIN chunk in .glb), then written
  // through a temporary file so a failed write never leaves half a file.
  const bool binary = is_glb(path);
  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, !binary, binary))
    throw GltfError(file, "tinygltf could not serialise the face");
  const std::string data = bytes.str();
  detail::write_file_atomically(
      path, [&data](std::ostream& out) { out.write(data.data(), static_cast<std::streamsize>(data.size())); });
}

}  // namespace performer
