// glTF writer: lays the SkinnedMesh streams out in one buffer, builds the node tree and skin, and
// lets tinygltf serialise it.
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include <tiny_gltf.h>

#include "performer/detail/atomic_file.h"
#include "gltf_buffer_view.h"
#include "performer/gltf_skin.h"

namespace performer {

namespace {

int add_accessor(tinygltf::Model& model, int view, int component_type, int type, std::size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

// POSITION accessors, morph targets' included, must carry their bounds (glTF 2.0, 3.7.2.1).
void set_bounds(tinygltf::Accessor& accessor, const std::vector<glm::vec3>& values) {
  glm::vec3 lo(0.0f), hi(0.0f);
  if (!values.empty()) lo = hi = values[0];
  for (const glm::vec3& p : values) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  accessor.minValues = {lo.x, lo.y, lo.z};
  accessor.maxValues = {hi.x, hi.y, hi.z};
}

int add_vec3_accessor(tinygltf::Model& model, const std::vector<glm::vec3>& values, bool bounds) {
  const int view =
      detail::append_buffer_view(model, values.data(), values.size() * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  const int accessor = add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, values.size());
  if (bounds) set_bounds(model.accessors[static_cast<std::size_t>(accessor)], values);
  return accessor;
}

bool is_identity(const glm::mat4& m) { return m == glm::mat4(1.0f); }

// TRS written only where it differs from the default, as exporters usually do.
void set_trs(tinygltf::Node& node, const SkinJoint& joint) {
  if (joint.translation != glm::vec3(0.0f))
    node.translation = {joint.translation.x, joint.translation.y, joint.translation.z};
  if (joint.rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f))  // glTF order is x, y, z, w
    node.rotation = {joint.rotation.x, joint.rotation.y, joint.rotation.z, joint.rotation.w};
  if (joint.scale != glm::vec3(1.0f)) node.scale = {joint.scale.x, joint.scale.y, joint.scale.z};
}

}  // namespace

void write_gltf_skinned(const std::filesystem::path& path, const SkinnedMesh& skinned,
                        std::span<const MorphTarget> morph_targets) {
  if (const std::string problem = skinned_mesh_problem(skinned); !problem.empty())
    throw std::invalid_argument("write_gltf_skinned: " + problem);
  const TriangleMesh& mesh = skinned.mesh;
  const std::size_t vertices = mesh.positions.size();
  const std::size_t joints = skinned.joints.size();
  for (const MorphTarget& t : morph_targets)
    if (t.position_deltas.size() != vertices || t.normal_deltas.size() != vertices)
      throw std::invalid_argument("write_gltf_skinned: morph target '" + t.name + "' does not cover the " +
                                  std::to_string(vertices) + " vertices");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "gpuj2k performer";
  model.buffers.emplace_back();

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = add_vec3_accessor(model, mesh.positions, true);
  if (!mesh.normals.empty()) primitive.attributes["NORMAL"] = add_vec3_accessor(model, mesh.normals, false);
  // Slots go out four per set; a set's unused slots get joint 0 and weight 0.
  const auto slots = static_cast<std::size_t>(skinned.influences);
  const std::size_t sets = (slots + 3) / 4;
  for (std::size_t set = 0; set < sets; ++set) {
    std::vector<std::uint16_t> set_joints(vertices * 4, 0);
    std::vector<float> set_weights(vertices * 4, 0.0f);
    for (std::size_t v = 0; v < vertices; ++v)
      for (std::size_t k = 0; k < 4 && set * 4 + k < slots; ++k) {
        set_joints[v * 4 + k] = skinned.joint_indices[v * slots + set * 4 + k];
        set_weights[v * 4 + k] = skinned.joint_weights[v * slots + set * 4 + k];
      }
    const int joint_view = detail::append_buffer_view(
        model, set_joints.data(), set_joints.size() * sizeof(std::uint16_t), TINYGLTF_TARGET_ARRAY_BUFFER);
    const int weight_view = detail::append_buffer_view(model, set_weights.data(), set_weights.size() * sizeof(float),
                                                       TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["JOINTS_" + std::to_string(set)] =
        add_accessor(model, joint_view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, vertices);
    primitive.attributes["WEIGHTS_" + std::to_string(set)] =
        add_accessor(model, weight_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, vertices);
  }
  {
    const int view = detail::append_buffer_view(model, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    primitive.indices =
        add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, mesh.indices.size());
  }
  tinygltf::Value::Array target_names;
  for (const MorphTarget& t : morph_targets) {
    primitive.targets.push_back({{"POSITION", add_vec3_accessor(model, t.position_deltas, true)},
                                 {"NORMAL", add_vec3_accessor(model, t.normal_deltas, false)}});
    target_names.emplace_back(t.name);
  }
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.primitives.push_back(primitive);
  if (!morph_targets.empty()) {
    gltf_mesh.weights.assign(morph_targets.size(), 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(std::move(target_names));
    gltf_mesh.extras = tinygltf::Value(std::move(extras));
  }
  model.meshes.push_back(gltf_mesh);

  tinygltf::Skin skin;
  {
    const int view = detail::append_buffer_view(model, skinned.inverse_bind.data(), joints * sizeof(glm::mat4), 0);
    skin.inverseBindMatrices = add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, joints);
  }

  // Joint j is node j. A joint with a non-identity `above` hangs from a node of its own holding it.
  model.nodes.resize(joints);
  std::vector<int> attach(joints);  // the node that goes under the parent (or into the scene) for joint j
  for (std::size_t j = 0; j < joints; ++j) {
    const SkinJoint& joint = skinned.joints[j];
    model.nodes[j].name = joint.name;
    set_trs(model.nodes[j], joint);
    attach[j] = static_cast<int>(j);
    skin.joints.push_back(static_cast<int>(j));
  }
  for (std::size_t j = 0; j < joints; ++j) {
    const SkinJoint& joint = skinned.joints[j];
    if (is_identity(joint.above)) continue;
    tinygltf::Node above;
    above.name = joint.name + "_above";
    above.matrix.assign(glm::value_ptr(joint.above), glm::value_ptr(joint.above) + 16);  // both column-major
    above.children.push_back(static_cast<int>(j));
    model.nodes.push_back(above);
    attach[j] = static_cast<int>(model.nodes.size() - 1);
  }
  tinygltf::Scene scene;
  for (std::size_t j = 0; j < joints; ++j) {
    const int parent = skinned.joints[j].parent;
    if (parent >= 0)
      model.nodes[static_cast<std::size_t>(parent)].children.push_back(attach[j]);
    else
      scene.nodes.push_back(attach[j]);
  }
  model.skins.push_back(skin);

  tinygltf::Node mesh_node;
  mesh_node.name = "skinned mesh";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  model.nodes.push_back(mesh_node);
  scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // Serialised in memory (buffer embedded: a data URI in JSON, the BIN chunk in .glb), then written
  // through a temporary file so a failed write never leaves half a file.
  const std::string file = path.string();
  const bool binary = path.extension() == ".glb" || path.extension() == ".GLB";
  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, !binary, binary)) throw GltfError(file, "cannot write file");
  const std::string data = bytes.str();
  try {
    detail::write_file_atomically(
        path, [&data](std::ostream& out) { out.write(data.data(), static_cast<std::streamsize>(data.size())); });
  } catch (const std::runtime_error& e) {
    // Its message is "PATH: problem"; the error type callers expect here is GltfError.
    std::string why = e.what();
    if (why.rfind(file + ": ", 0) == 0) why.erase(0, file.size() + 2);
    throw GltfError(file, why);
  }
}

}  // namespace performer
