#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "performer/detail/face_normals.h"
#include "gltf_accessor.h"
#include "gltf_load.h"
#include "performer/gltf_face.h"
#include "performer/gltf_skin.h"
#include "performer/procedural_head.h"

namespace performer {

namespace {

bool has_targets(const tinygltf::Mesh& mesh) {
  return std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                     [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
}

std::size_t find_mesh(const tinygltf::Model& model, const std::string& name, const std::string& file) {
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    if (!name.empty() ? model.meshes[m].name == name : has_targets(model.meshes[m])) return m;
  }
  if (!name.empty()) throw GltfError(file, "no mesh named '" + name + "'");
  throw GltfError(file, "no mesh has morph targets (a face needs its visemes and expressions as morph targets)");
}

// Morph target names: mesh.extras.targetNames, the convention Blender and most exporters follow;
// some put them on the first primitive instead.
std::vector<std::string> target_names(const tinygltf::Mesh& mesh, std::size_t count, const std::string& file,
                                      const std::string& what) {
  const tinygltf::Value* extras = &mesh.extras;
  if (!(extras->IsObject() && extras->Has("targetNames")) && !mesh.primitives.empty())
    extras = &mesh.primitives.front().extras;
  if (!(extras->IsObject() && extras->Has("targetNames")))
    throw GltfError(file, what + ": morph targets have no names (expected mesh.extras.targetNames)");
  const tinygltf::Value& names = extras->Get("targetNames");
  if (!names.IsArray() || names.ArrayLen() != count)
    throw GltfError(file, what + ": extras.targetNames should list " + std::to_string(count) + " names");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < count; ++i) {
    const tinygltf::Value& n = names.Get(static_cast<int>(i));
    if (!n.IsString()) throw GltfError(file, what + ": target name " + std::to_string(i) + " is not a string");
    out.push_back(n.Get<std::string>());
  }
  return out;
}

// The merged primitives of one mesh.
struct RawMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
  bool file_normals = true;  // every primitive had NORMAL
  std::vector<std::vector<glm::vec3>> position_deltas, normal_deltas;
  std::vector<bool> file_normal_deltas;  // per target: every primitive had its NORMAL
};

std::vector<glm::vec3> read_vec3(const tinygltf::Model& model, int accessor, const std::string& file,
                                 const std::string& what) {
  const detail::AccessorValues a = detail::read_accessor(
      model, accessor, TINYGLTF_TYPE_VEC3,
      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
       TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
      file, what);
  std::vector<glm::vec3> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i)
    out[i] = glm::vec3(static_cast<float>(a.values[3 * i]), static_cast<float>(a.values[3 * i + 1]),
                       static_cast<float>(a.values[3 * i + 2]));
  for (const glm::vec3& v : out)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw GltfError(file, what + ": non-finite value");
  return out;
}

// Triangle corners of a primitive as indices into its own vertices: lists as they are, strips and
// fans unrolled (keeping the winding), no indices meaning 0, 1, 2, ...
std::vector<std::uint32_t> triangle_corners(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                            std::size_t vertices, const std::string& file, const std::string& what) {
  std::vector<std::uint32_t> order;
  if (prim.indices >= 0) {
    const detail::AccessorValues a =
        detail::read_accessor(model, prim.indices, TINYGLTF_TYPE_SCALAR,
                              {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                               TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                              file, what + " indices");
    order.reserve(a.count);
    for (const double v : a.values) {
      if (v >= static_cast<double>(vertices))
        throw GltfError(file, what + ": index " + std::to_string(static_cast<std::uint64_t>(v)) + " past its " +
                                  std::to_string(vertices) + " vertices");
      order.push_back(static_cast<std::uint32_t>(v));
    }
  } else {
    for (std::size_t i = 0; i < vertices; ++i) order.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> tris;
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (order.size() % 3 != 0) throw GltfError(file, what + ": triangle list length is not a multiple of 3");
    tris = order;
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < order.size(); ++i) {
      if (i % 2 == 0)
        tris.insert(tris.end(), {order[i], order[i + 1], order[i + 2]});
      else
        tris.insert(tris.end(), {order[i + 1], order[i], order[i + 2]});
    }
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 1; i + 1 < order.size(); ++i) tris.insert(tris.end(), {order[0], order[i], order[i + 1]});
  }
  return tris;
}

RawMesh read_mesh(const tinygltf::Model& model, const tinygltf::Mesh& mesh, std::size_t target_count,
                  const std::string& file, const std::string& what) {
  RawMesh raw;
  raw.position_deltas.resize(target_count);
  raw.normal_deltas.resize(target_count);
  raw.file_normal_deltas.assign(target_count, true);
  bool any_triangles = false;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string pw = what + " primitive " + std::to_string(p);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    // Points and lines have no surface to deform and light; they are not part of the face.
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      continue;
    any_triangles = true;
    const auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) throw GltfError(file, pw + " has no POSITION");
    const std::vector<glm::vec3> positions = read_vec3(model, pos_it->second, file, pw + " POSITION");
    const std::size_t n = positions.size();
    std::vector<glm::vec3> normals(n, glm::vec3(0.0f));
    if (const auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
      normals = read_vec3(model, it->second, file, pw + " NORMAL");
      if (normals.size() != n) throw GltfError(file, pw + ": NORMAL and POSITION counts differ");
    } else {
      raw.file_normals = false;
    }
    // glTF requires every primitive of a mesh to have the same number of morph targets.
    if (prim.targets.size() != target_count)
      throw GltfError(file, pw + " has " + std::to_string(prim.targets.size()) + " morph targets, the mesh names " +
                                std::to_string(target_count));
    const auto base = static_cast<std::uint32_t>(raw.positions.size());
    for (std::size_t t = 0; t < target_count; ++t) {
      const auto& attrs = prim.targets[t];
      std::vector<glm::vec3> dp(n, glm::vec3(0.0f)), dn(n, glm::vec3(0.0f));
      const std::string tw = pw + " target " + std::to_string(t);
      if (const auto it = attrs.find("POSITION"); it != attrs.end()) {
        dp = read_vec3(model, it->second, file, tw + " POSITION");
        if (dp.size() != n) throw GltfError(file, tw + ": POSITION count differs from the primitive's");
      }
      if (const auto it = attrs.find("NORMAL"); it != attrs.end()) {
        dn = read_vec3(model, it->second, file, tw + " NORMAL");
        if (dn.size() != n) throw GltfError(file, tw + ": NORMAL count differs from the primitive's");
      } else {
        raw.file_normal_deltas[t] = false;
      }
      raw.position_deltas[t].insert(raw.position_deltas[t].end(), dp.begin(), dp.end());
      raw.normal_deltas[t].insert(raw.normal_deltas[t].end(), dn.begin(), dn.end());
    }
    for (const std::uint32_t i : triangle_corners(model, prim, n, file, pw)) raw.indices.push_back(base + i);
    raw.positions.insert(raw.positions.end(), positions.begin(), positions.end());
    raw.normals.insert(raw.normals.end(), normals.begin(), normals.end());
  }
  if (!any_triangles || raw.indices.empty()) throw GltfError(file, what + " has no triangles");
  if (raw.positions.size() > std::size_t{0xffffffff}) throw GltfError(file, what + " has too many vertices");
  return raw;
}

// Normals the file left out, from the geometry: the neutral ones, and each target's normal DV as the
// change of the computed normal (computed against computed, so the DV is zero where the target
// does not move even when the file's own normals differ from computed ones).
void complete_normals(RawMesh& raw) {
  const std::size_t n = raw.positions.size();
  std::vector<glm::vec3> computed(n);
  detail::unit_vertex_normals(raw.positions, raw.indices, {}, computed);
  if (!raw.file_normals) {
    raw.normals = computed;
  } else {
    // Unit length as the specification requires (files that already comply are kept bit for bit);
    // a zero normal in the file takes the computed one.
    for (std::size_t v = 0; v < n; ++v) {
      const float len = glm::length(raw.normals[v]);
      if (std::abs(len - 1.0f) > 1e-4f) raw.normals[v] = len > 1e-12f ? raw.normals[v] / len : computed[v];
    }
  }
  std::vector<glm::vec3> moved(n), target(n);
  for (std::size_t t = 0; t < raw.position_deltas.size(); ++t) {
    if (raw.file_normal_deltas[t]) continue;
    for (std::size_t v = 0; v < n; ++v) moved[v] = raw.positions[v] + raw.position_deltas[t][v];
    detail::unit_vertex_normals(moved, raw.indices, computed, target);
    for (std::size_t v = 0; v < n; ++v) raw.normal_deltas[t][v] = target[v] - computed[v];
  }
}

bool same_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// The file's morph with this name: exact match first, then ignoring case; -1 when none.
int morph_index(const std::vector<std::string>& names, std::string_view name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (same_ignoring_case(names[i], name)) return static_cast<int>(i);
  return -1;
}

struct Resolved {
  std::vector<std::pair<int, float>> parts;  // (morph index, weight)
  std::string source;
};

Resolved from_morph(const std::vector<std::string>& names, int index) {
  return {{{index, 1.0f}}, names[static_cast<std::size_t>(index)]};
}

// A recipe's ingredients that the file has; empty when none.
Resolved from_recipe(const std::vector<std::string>& names, const MorphRecipe& recipe) {
  Resolved r;
  for (const MorphIngredient& ing : recipe.ingredients) {
    const int i = morph_index(names, ing.morph);
    if (i < 0) continue;
    if (!r.source.empty()) r.source += " + ";
    std::string w = std::to_string(ing.weight);
    while (w.size() > 1 && w.back() == '0') w.pop_back();
    if (!w.empty() && w.back() == '.') w.pop_back();
    r.source += w + "*" + names[static_cast<std::size_t>(i)];
    r.parts.emplace_back(i, ing.weight);
  }
  return r;
}

Resolved resolve_viseme(const VisemeInfo& v, const std::vector<std::string>& names, const MorphMapping& mapping) {
  if (const int i = morph_index(names, v.name); i >= 0) return from_morph(names, i);
  const std::vector<std::string>& oculus = mapping.oculus_morphs(v.oculus);
  for (const std::string& name : oculus)
    if (const int i = morph_index(names, name); i >= 0) return from_morph(names, i);
  for (const std::string& name : oculus)
    if (const MorphRecipe* r = mapping.recipe(name))
      if (Resolved res = from_recipe(names, *r); !res.parts.empty()) return res;
  return {};
}

Resolved resolve_expression(std::string_view e, const std::vector<std::string>& names, const MorphMapping& mapping) {
  if (const int i = morph_index(names, e); i >= 0) return from_morph(names, i);
  if (const MorphRecipe* r = mapping.recipe(e)) return from_recipe(names, *r);
  return {};
}

MorphTarget build_target(const std::string& name, const Resolved& r, const RawMesh& raw) {
  MorphTarget t;
  t.name = name;
  const std::size_t n = raw.positions.size();
  t.position_deltas.assign(n, glm::vec3(0.0f));
  t.normal_deltas.assign(n, glm::vec3(0.0f));
  // A single morph at weight 1 is copied, so a round trip through write_gltf_face is exact.
  if (r.parts.size() == 1 && r.parts.front().second == 1.0f) {
    t.position_deltas = raw.position_deltas[static_cast<std::size_t>(r.parts.front().first)];
    t.normal_deltas = raw.normal_deltas[static_cast<std::size_t>(r.parts.front().first)];
    return t;
  }
  // Sums of DVs are DVs (3.6); the normal DVs sum the same way, as 3.11 blends them linearly.
  for (const auto& [index, weight] : r.parts)
    for (std::size_t v = 0; v < n; ++v) {
      t.position_deltas[v] += weight * raw.position_deltas[static_cast<std::size_t>(index)][v];
      t.normal_deltas[v] += weight * raw.normal_deltas[static_cast<std::size_t>(index)][v];
    }
  return t;
}

std::string join(const std::vector<std::string>& items, std::size_t limit) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < limit; ++i) out += (i ? ", " : "") + items[i];
  if (items.size() > limit) out += ", ... (" + std::to_string(items.size()) + " in all)";
  return out;
}

}  // namespace

namespace detail {

GltfFace read_gltf_face(const tinygltf::Model& model, std::size_t mesh_index, const VisemeSet& set,
                        const MorphMapping& mapping, const GltfFaceOptions& options, const std::string& file,
                        bool allow_no_match) {
  const tinygltf::Mesh& mesh = model.meshes[mesh_index];
  GltfFace out;
  out.mesh = mesh.name.empty() ? "mesh " + std::to_string(mesh_index) : mesh.name;
  const std::string what = "mesh '" + out.mesh + "'";
  std::size_t target_count = 0;
  for (const tinygltf::Primitive& p : mesh.primitives) target_count = std::max(target_count, p.targets.size());
  if (target_count == 0) throw GltfError(file, what + " has no morph targets");
  const std::vector<std::string> names = target_names(mesh, target_count, file, what);
  RawMesh raw = read_mesh(model, mesh, target_count, file, what);
  complete_normals(raw);

  out.model.positions = raw.positions;
  out.model.normals = raw.normals;
  out.model.indices = raw.indices;
  bool found_any = false;
  auto take = [&](const std::string& name, const Resolved& r) {
    if (r.parts.empty()) {
      out.missing.push_back(name);
      return;
    }
    found_any = true;
    out.model.targets.push_back(build_target(name, r, raw));
    out.sources.push_back(r.source);
  };
  for (const VisemeInfo& v : set.visemes) {
    Resolved r = resolve_viseme(v, names, mapping);
    // The silent viseme is the neutral face itself (3.5): a zero DV when the rig has no morph for
    // it. Not counted as found, so a file with nothing we need still fails below.
    if (r.parts.empty() && v.oculus == "sil") {
      MorphTarget zero{v.name, std::vector<glm::vec3>(raw.positions.size(), glm::vec3(0.0f)),
                       std::vector<glm::vec3>(raw.positions.size(), glm::vec3(0.0f))};
      out.model.targets.push_back(std::move(zero));
      out.sources.emplace_back("neutral");
      continue;
    }
    take(v.name, r);
  }
  for (const std::string_view e : kHeadExpressions) take(std::string(e), resolve_expression(e, names, mapping));
  // Further expressions that arkit.tsv defines (a user's "disgust"): taken when the file supplies
  // them, not reported missing when it does not, since nothing asked for them.
  for (const MorphRecipe& r : mapping.recipes) {
    const bool oculus_stand_in = std::any_of(mapping.oculus.begin(), mapping.oculus.end(), [&r](const auto& o) {
      return std::find(o.morphs.begin(), o.morphs.end(), r.target) != o.morphs.end();
    });
    if (oculus_stand_in || out.model.find_target(r.target) >= 0 || set.find(r.target) >= 0 ||
        std::find(out.missing.begin(), out.missing.end(), r.target) != out.missing.end())
      continue;
    if (Resolved res = resolve_expression(r.target, names, mapping); !res.parts.empty()) take(r.target, res);
  }

  if (!found_any && allow_no_match) {
    out.model.targets.clear();
    out.sources.clear();
    validate_face_model(out.model, file);
    return out;
  }
  if (!found_any)
    throw GltfError(file, what +
                              " has none of the morph targets the performer needs (visemes as viseme_* Oculus "
                              "names or our names, expressions and blink as ARKit blend shapes or our names); "
                              "missing: " +
                              join(out.missing, 40) + "; the file has: " + join(names, 20));
  if (options.require_all && !out.missing.empty())
    throw GltfError(file, what + " lacks morph targets for: " + join(out.missing, 40));
  validate_face_model(out.model, file);
  return out;
}

}  // namespace detail

GltfFace load_gltf_face(const std::filesystem::path& path, const VisemeSet& set, const MorphMapping& mapping,
                        const GltfFaceOptions& options) {
  const std::string file = path.string();
  const tinygltf::Model model = detail::load_gltf_model(path);
  return detail::read_gltf_face(model, find_mesh(model, options.mesh, file), set, mapping, options, file);
}

GltfFace load_gltf_face(const std::filesystem::path& path, const VisemeSet& set, const GltfFaceOptions& options) {
  return load_gltf_face(path, set, load_morph_mapping(default_morph_dir()), options);
}

}  // namespace performer
