#include "performer/procedural_head.h"

#include <stdexcept>
#include <string>

#include "performer/detail/face_normals.h"
#include "head_grid.h"
#include "head_poses.h"
#include "head_shape.h"
#include "base/thread_pool.h"

namespace performer {

namespace {

void check_params(const HeadParams& p) {
  auto fail = [](const std::string& problem) { throw std::invalid_argument("procedural head: " + problem); };
  if (p.rings < 24 || p.rings > 2048) fail("rings " + std::to_string(p.rings) + " outside 24..2048");
  if (p.segments < 24 || p.segments > 4096 || p.segments % 2 != 0)
    fail("segments " + std::to_string(p.segments) + " must be even, 24..4096");
  if (p.mouth_rows < 1 || p.mouth_rows > 8) fail("mouth_rows " + std::to_string(p.mouth_rows) + " outside 1..8");
  if (!(p.focus >= 0.0f && p.focus <= 3.0f)) fail("focus outside 0..3");
  if (!(p.scale > 0.0f && p.scale < 1e3f)) fail("scale must be positive");
}

// One target: the pose applied to the neutral mesh, its normals recomputed, both stored as
// differences from the neutral (equations 3.5 and 3.11).
MorphTarget make_target(std::string name, const detail::FacePose& pose, const detail::HeadLandmarks& marks,
                        const detail::HeadGrid& grid, const std::vector<detail::HeadVertexParam>& params,
                        const FaceModel& neutral, int slit_rows) {
  const std::size_t n = neutral.positions.size();
  std::vector<glm::vec3> positions(n), normals(n);
  detail::pose_head(marks, params, grid.mouth_theta, slit_rows, neutral.positions, pose, positions);
  detail::unit_vertex_normals(positions, neutral.indices, neutral.normals, normals);
  MorphTarget t;
  t.name = std::move(name);
  t.position_deltas.resize(n);
  t.normal_deltas.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    t.position_deltas[v] = positions[v] - neutral.positions[v];
    t.normal_deltas[v] = normals[v] - neutral.normals[v];
  }
  return t;
}

}  // namespace

FaceModel build_procedural_head(const VisemeSet& set, const HeadParams& params) {
  check_params(params);
  const detail::HeadLandmarks marks;
  const detail::HeadGrid grid =
      detail::make_head_grid(marks, params.rings, params.segments, params.mouth_rows, params.focus);
  const std::vector<detail::HeadVertexParam> vertex_params = grid.vertex_params();

  FaceModel model;
  model.positions.resize(vertex_params.size());
  // Each step is a pure function of the parameters (the row alignment per column), so threading
  // cannot change the result.
  base::parallel_for(vertex_params.size(), 512, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) model.positions[v] = detail::base_head_point(marks, vertex_params[v]);
  });
  detail::align_rows_to_eyelids(marks, grid, model.positions);
  base::parallel_for(vertex_params.size(), 512, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      model.positions[v] =
          detail::face_head_point(marks, vertex_params[v], model.positions[v], grid.mouth_theta, params.mouth_rows);
  });
  model.indices = grid.triangles();
  model.normals.resize(model.positions.size());
  detail::unit_vertex_normals(model.positions, model.indices, {}, model.normals);

  std::vector<std::pair<std::string, detail::FacePose>> poses;
  for (const VisemeInfo& v : set.visemes) {
    const auto pose = detail::viseme_pose(v.name, v.oculus);
    if (!pose)
      throw std::invalid_argument("procedural head: no shape for viseme '" + v.name + "' (Oculus '" + v.oculus + "')");
    poses.emplace_back(v.name, *pose);
  }
  for (const std::string_view e : kHeadExpressions) {
    if (set.find(e) >= 0)
      throw std::invalid_argument("procedural head: viseme named like the expression '" + std::string(e) + "'");
    poses.emplace_back(std::string(e), *detail::expression_pose(e));
  }

  model.targets.resize(poses.size());
  // Targets are independent of each other: one per task.
  base::parallel_for(poses.size(), 1, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
      model.targets[t] =
          make_target(poses[t].first, poses[t].second, marks, grid, vertex_params, model, params.mouth_rows);
  });

  if (params.scale != 1.0f) {
    for (glm::vec3& p : model.positions) p *= params.scale;
    for (MorphTarget& t : model.targets)
      for (glm::vec3& d : t.position_deltas) d *= params.scale;
  }
  return model;
}

}  // namespace performer
