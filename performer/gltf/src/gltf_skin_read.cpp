// glTF reader: tinygltf parses the JSON and loads the buffers; this file picks out the skinned
// mesh and checks everything it uses, since tinygltf leaves most index and range checks to its
// caller.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_accessor.h"
#include "gltf_load.h"
#include "performer/gltf_skin.h"
#include "performer/mesh_normals.h"
#include "performer/ssd_weights.h"

namespace performer {

GltfError::GltfError(std::string file, std::string problem)
    : std::runtime_error(file + ": " + problem), file_(std::move(file)), problem_(std::move(problem)) {}

namespace {

using detail::read_accessor;

struct Trs {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
};

// A node's local transform as TRS. A `matrix` is split into TRS (the specification requires it to
// be decomposable: no shear), a mirroring determinant going to the x scale.
Trs node_trs(const tinygltf::Node& node, const std::string& file, int index) {
  Trs trs;
  const std::string what = "node " + std::to_string(index);
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) throw GltfError(file, what + ": matrix needs 16 numbers");
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
    trs.translation = glm::vec3(m[3]);
    glm::dvec3 axes[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
    glm::dvec3 scale(glm::length(axes[0]), glm::length(axes[1]), glm::length(axes[2]));
    if (glm::dot(glm::cross(axes[0], axes[1]), axes[2]) < 0.0) scale.x = -scale.x;
    if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0) throw GltfError(file, what + ": matrix has a zero scale");
    const glm::dmat3 rotation(axes[0] / scale.x, axes[1] / scale.y, axes[2] / scale.z);
    trs.rotation = glm::quat(glm::quat_cast(rotation));
    trs.scale = glm::vec3(scale);
    return trs;
  }
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) throw GltfError(file, what + ": translation needs 3 numbers");
    trs.translation = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) throw GltfError(file, what + ": rotation needs 4 numbers");
    // glTF quaternions are (x, y, z, w); glm's constructor takes w first.
    trs.rotation =
        glm::normalize(glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                 static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])));
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) throw GltfError(file, what + ": scale needs 3 numbers");
    trs.scale = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
  }
  return trs;
}

glm::mat4 trs_matrix(const Trs& t) {
  return glm::scale(glm::translate(glm::mat4(1.0f), t.translation) * glm::mat4_cast(t.rotation), t.scale);
}

// parent[n]: the node listing n as a child, -1 for none.
std::vector<int> node_parents(const tinygltf::Model& model, const std::string& file) {
  std::vector<int> parent(model.nodes.size(), -1);
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    for (const int child : model.nodes[n].children) {
      if (child < 0 || static_cast<std::size_t>(child) >= model.nodes.size())
        throw GltfError(file,
                        "node " + std::to_string(n) + " has child " + std::to_string(child) + ", which does not exist");
      if (parent[static_cast<std::size_t>(child)] >= 0 || static_cast<std::size_t>(child) == n)
        throw GltfError(file, "node " + std::to_string(child) + " has more than one parent");
      parent[static_cast<std::size_t>(child)] = static_cast<int>(n);
    }
  return parent;
}

void read_skin(const tinygltf::Model& model, int skin_index, SkinnedMesh& out, const std::string& file) {
  const tinygltf::Skin& skin = model.skins[static_cast<std::size_t>(skin_index)];
  const std::string what = "skin " + std::to_string(skin_index);
  if (skin.joints.empty()) throw GltfError(file, what + " has no joints");
  if (skin.joints.size() > 65536) throw GltfError(file, what + " has more joints than 16-bit indices can name");
  const std::vector<int> parent = node_parents(model, file);
  std::vector<int> joint_of_node(model.nodes.size(), -1);
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size())
      throw GltfError(file, what + " names node " + std::to_string(node) + ", which does not exist");
    if (joint_of_node[static_cast<std::size_t>(node)] >= 0)
      throw GltfError(file, what + " lists node " + std::to_string(node) + " twice");
    joint_of_node[static_cast<std::size_t>(node)] = static_cast<int>(j);
  }
  out.joints.resize(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    SkinJoint& joint = out.joints[j];
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
    joint.name = n.name;
    const Trs trs = node_trs(n, file, node);
    joint.translation = trs.translation;
    joint.rotation = trs.rotation;
    joint.scale = trs.scale;
    // Up to the nearest joint, collecting the transforms of plain nodes on the way. Children lists
    // with one parent each cannot loop back, but a bound keeps a malformed file from spinning.
    int up = parent[static_cast<std::size_t>(node)];
    for (std::size_t steps = 0; up >= 0 && joint_of_node[static_cast<std::size_t>(up)] < 0; ++steps) {
      if (steps > model.nodes.size()) throw GltfError(file, "the node hierarchy has a cycle");
      joint.above = trs_matrix(node_trs(model.nodes[static_cast<std::size_t>(up)], file, up)) * joint.above;
      up = parent[static_cast<std::size_t>(up)];
    }
    joint.parent = up >= 0 ? joint_of_node[static_cast<std::size_t>(up)] : -1;
  }
  out.inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));  // the specification's default
  if (skin.inverseBindMatrices >= 0) {
    const detail::AccessorValues m =
        read_accessor(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, {TINYGLTF_COMPONENT_TYPE_FLOAT}, file,
                      what + " inverseBindMatrices");
    if (m.count < skin.joints.size())
      throw GltfError(file, what + ": " + std::to_string(m.count) + " inverse bind matrices for " +
                                std::to_string(skin.joints.size()) + " joints");
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      for (int k = 0; k < 16; ++k)
        glm::value_ptr(out.inverse_bind[j])[k] = static_cast<float>(m.values[j * 16 + static_cast<std::size_t>(k)]);
  }
}

// Triangle list of one primitive: its indices (or 0..n-1), strips and fans unrolled, in range.
std::vector<std::uint32_t> primitive_triangles(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                               std::size_t vertex_count, const std::string& file,
                                               const std::string& what) {
  std::vector<std::uint32_t> order;
  if (primitive.indices >= 0) {
    const detail::AccessorValues ix =
        read_accessor(model, primitive.indices, TINYGLTF_TYPE_SCALAR,
                      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                      file, what + " indices");
    order.reserve(ix.count);
    for (const double v : ix.values) {
      if (v >= static_cast<double>(vertex_count))
        throw GltfError(file, what + ": vertex index " + std::to_string(static_cast<std::uint64_t>(v)) + " of " +
                                  std::to_string(vertex_count) + " vertices");
      order.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    order.resize(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v) order[v] = static_cast<std::uint32_t>(v);
  }
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  std::vector<std::uint32_t> triangles;
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
      if (order.size() % 3 != 0) throw GltfError(file, what + ": index count is not a multiple of 3");
      return order;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      // Every other triangle of a strip is swapped so that all keep the first one's winding.
      for (std::size_t i = 0; i + 2 < order.size(); ++i)
        triangles.insert(triangles.end(), {order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]});
      return triangles;
    case TINYGLTF_MODE_TRIANGLE_FAN:
      for (std::size_t i = 0; i + 2 < order.size(); ++i)
        triangles.insert(triangles.end(), {order[i + 1], order[i + 2], order[0]});
      return triangles;
    default:
      throw GltfError(file, what + ": mode " + std::to_string(mode) + " is not triangles");
  }
}

bool has(const tinygltf::Primitive& p, const std::string& attribute) { return p.attributes.count(attribute) != 0; }

void read_mesh(const tinygltf::Model& model, int mesh_index, SkinnedMesh& out, const std::string& file) {
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
  if (mesh.primitives.empty()) throw GltfError(file, "mesh " + std::to_string(mesh_index) + " has no primitives");
  bool second_set = true;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    const std::string what = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
    for (const char* required : {"POSITION", "JOINTS_0", "WEIGHTS_0"})
      if (!has(primitive, required)) throw GltfError(file, what + " has no " + required);
    second_set = second_set && has(primitive, "JOINTS_1") && has(primitive, "WEIGHTS_1");
  }
  const int sets = second_set ? 2 : 1;
  out.influences = 4 * sets;
  static_assert(kMaxInfluences >= 8);

  std::vector<bool> normal_known;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    const std::string what = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
    const detail::AccessorValues pos = read_accessor(model, primitive.attributes.at("POSITION"), TINYGLTF_TYPE_VEC3,
                                                     {TINYGLTF_COMPONENT_TYPE_FLOAT}, file, what + " POSITION");
    const std::size_t n = pos.count, base = out.mesh.positions.size();
    if (base + n > 0xffffffffu) throw GltfError(file, what + ": more than 2^32 - 1 vertices");
    for (std::size_t v = 0; v < n; ++v)
      out.mesh.positions.emplace_back(pos.values[3 * v], pos.values[3 * v + 1], pos.values[3 * v + 2]);
    if (has(primitive, "NORMAL")) {
      const detail::AccessorValues nor = read_accessor(model, primitive.attributes.at("NORMAL"), TINYGLTF_TYPE_VEC3,
                                                       {TINYGLTF_COMPONENT_TYPE_FLOAT}, file, what + " NORMAL");
      if (nor.count != n) throw GltfError(file, what + ": NORMAL and POSITION counts differ");
      for (std::size_t v = 0; v < n; ++v) {
        const glm::vec3 normal(nor.values[3 * v], nor.values[3 * v + 1], nor.values[3 * v + 2]);
        const float length = glm::length(normal);
        const bool usable = length > 0.0f && std::isfinite(length);
        // Unit normals are kept bit for bit; others are normalised.
        out.mesh.normals.push_back(!usable                            ? glm::vec3(0.0f)
                                   : std::abs(length - 1.0f) <= 1e-6f ? normal
                                                                      : normal / length);
        normal_known.push_back(usable);
      }
    } else {
      out.mesh.normals.resize(base + n, glm::vec3(0.0f));
      normal_known.resize(base + n, false);
    }

    // Joints and weights, set after set, into 4 * sets slots per vertex.
    const auto slots = static_cast<std::size_t>(out.influences);
    out.joint_indices.resize((base + n) * slots, 0);
    out.joint_weights.resize((base + n) * slots, 0.0f);
    for (int set = 0; set < sets; ++set) {
      const std::string joints_name = "JOINTS_" + std::to_string(set), weights_name = "WEIGHTS_" + std::to_string(set);
      const detail::AccessorValues joints =
          read_accessor(model, primitive.attributes.at(joints_name), TINYGLTF_TYPE_VEC4,
                        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, file,
                        what + " " + joints_name);
      const detail::AccessorValues weights =
          read_accessor(model, primitive.attributes.at(weights_name), TINYGLTF_TYPE_VEC4,
                        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                        file, what + " " + weights_name);
      if (joints.count != n || weights.count != n)
        throw GltfError(file, what + ": " + joints_name + " or " + weights_name + " count differs from POSITION");
      for (std::size_t v = 0; v < n; ++v)
        for (std::size_t k = 0; k < 4; ++k) {
          const double joint = joints.values[4 * v + k];
          const double weight = weights.values[4 * v + k];
          if (joint >= static_cast<double>(out.joints.size()))
            throw GltfError(file, what + ": " + joints_name + " of vertex " + std::to_string(v) + " names joint " +
                                      std::to_string(static_cast<long>(joint)) + " of " +
                                      std::to_string(out.joints.size()));
          if (!(weight >= 0.0) || !std::isfinite(weight))
            throw GltfError(
                file, what + ": " + weights_name + " of vertex " + std::to_string(v) + " is negative or not a number");
          const std::size_t slot = (base + v) * slots + static_cast<std::size_t>(set) * 4 + k;
          out.joint_indices[slot] = static_cast<std::uint16_t>(joint);
          out.joint_weights[slot] = static_cast<float>(weight);
        }
    }
    // Normalised here: 8-bit weights in particular rarely add up to exactly 1. Sums already 1 to
    // float precision are left alone, so float weights survive a write and read bit for bit.
    for (std::size_t v = 0; v < n; ++v) {
      float* w = out.joint_weights.data() + (base + v) * slots;
      double sum = 0.0;
      for (std::size_t k = 0; k < slots; ++k) sum += w[k];
      if (!(sum > 0.0)) throw GltfError(file, what + ": the weights of vertex " + std::to_string(v) + " sum to zero");
      if (std::abs(sum - 1.0) <= 1e-6) continue;
      for (std::size_t k = 0; k < slots; ++k) w[k] = static_cast<float>(w[k] / sum);
    }

    for (const std::uint32_t i : primitive_triangles(model, primitive, n, file, what))
      out.mesh.indices.push_back(static_cast<std::uint32_t>(base + i));
  }

  // Normals the file did not give (or gave as zero) come from the triangles around the vertex.
  if (std::find(normal_known.begin(), normal_known.end(), false) != normal_known.end()) {
    std::vector<glm::vec3> computed(out.mesh.positions.size());
    area_weighted_normals(out.mesh.positions, out.mesh.indices, computed);
    for (std::size_t v = 0; v < computed.size(); ++v)
      if (!normal_known[v])
        out.mesh.normals[v] = computed[v] == glm::vec3(0.0f) ? glm::vec3(0.0f, 0.0f, 1.0f) : computed[v];
  }
}

}  // namespace

namespace detail {

int first_skinned_node(const tinygltf::Model& model) {
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].mesh >= 0 && model.nodes[n].skin >= 0) return static_cast<int>(n);
  return -1;
}

SkinnedMesh read_skinned_node(const tinygltf::Model& model, int node_index, const std::string& file) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
  if (static_cast<std::size_t>(node.mesh) >= model.meshes.size())
    throw GltfError(file, "node " + std::to_string(node_index) + " names mesh " + std::to_string(node.mesh) +
                              ", which does not exist");
  if (static_cast<std::size_t>(node.skin) >= model.skins.size())
    throw GltfError(file, "node " + std::to_string(node_index) + " names skin " + std::to_string(node.skin) +
                              ", which does not exist");
  SkinnedMesh out;
  read_skin(model, node.skin, out, file);
  read_mesh(model, node.mesh, out, file);
  return out;
}

}  // namespace detail

SkinnedMesh read_gltf_skinned(const std::filesystem::path& path) {
  const std::string file = path.string();
  const tinygltf::Model model = detail::load_gltf_model(path);
  const int node_index = detail::first_skinned_node(model);
  if (node_index < 0) throw GltfError(file, model.skins.empty() ? "no skin" : "no node has both a mesh and a skin");
  return detail::read_skinned_node(model, node_index, file);
}

}  // namespace performer
