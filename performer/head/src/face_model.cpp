#include "performer/face_model.h"

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace performer {

int FaceModel::find_target(std::string_view name) const {
  for (std::size_t i = 0; i < targets.size(); ++i)
    if (targets[i].name == name) return static_cast<int>(i);
  return -1;
}

const MorphTarget* FaceModel::target(std::string_view name) const {
  const int i = find_target(name);
  return i < 0 ? nullptr : &targets[static_cast<std::size_t>(i)];
}

namespace {

bool finite(const std::vector<glm::vec3>& v) {
  for (const glm::vec3& p : v)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

}  // namespace

void validate_face_model(const FaceModel& model, std::string_view what) {
  const std::string label(what);
  auto fail = [&label](const std::string& problem) { throw std::invalid_argument(label + ": " + problem); };
  const std::size_t n = model.positions.size();
  if (n == 0) fail("face model has no vertices");
  if (model.normals.size() != n)
    fail(std::to_string(n) + " positions but " + std::to_string(model.normals.size()) + " normals");
  if (model.indices.size() % 3 != 0)
    fail(std::to_string(model.indices.size()) + " indices is not a whole number of triangles");
  for (std::size_t i = 0; i < model.indices.size(); ++i)
    if (model.indices[i] >= n)
      fail("index " + std::to_string(i) + " is " + std::to_string(model.indices[i]) + ", past the " +
           std::to_string(n) + " vertices");
  if (!finite(model.positions) || !finite(model.normals)) fail("neutral mesh has a non-finite value");
  std::set<std::string, std::less<>> names;
  for (const MorphTarget& t : model.targets) {
    if (t.name.empty()) fail("a morph target has no name");
    if (!names.insert(t.name).second) fail("morph target '" + t.name + "' repeated");
    if (t.position_deltas.size() != n || t.normal_deltas.size() != n)
      fail("morph target '" + t.name + "' has " + std::to_string(t.position_deltas.size()) + " position and " +
           std::to_string(t.normal_deltas.size()) + " normal deltas for " + std::to_string(n) + " vertices");
    if (!finite(t.position_deltas) || !finite(t.normal_deltas))
      fail("morph target '" + t.name + "' has a non-finite delta");
  }
}

}  // namespace performer
