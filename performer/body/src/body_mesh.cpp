#include "performer/body_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "performer/local_transforms.h"
#include "performer/marching_cubes.h"
#include "performer/mesh_normals.h"
#include "base/thread_pool.h"
#include "performer/scalar_grid.h"
#include "performer/world_transforms.h"

namespace performer {

namespace {

// Central-difference gradient of the field, for the rare vertex whose triangles have no area.
glm::vec3 field_normal(const BodyShape& shape, const glm::vec3& p, float h) {
  const glm::vec3 dx(h, 0, 0), dy(0, h, 0), dz(0, 0, h);
  const glm::vec3 g(body_field(shape, p + dx) - body_field(shape, p - dx),
                    body_field(shape, p + dy) - body_field(shape, p - dy),
                    body_field(shape, p + dz) - body_field(shape, p - dz));
  const float length = glm::length(g);
  return length > 0.0f ? g / length : glm::vec3(0.0f, 1.0f, 0.0f);
}

std::vector<glm::mat4> rest_world(const Skeleton& skeleton) {
  std::vector<glm::mat4> local(skeleton.joints.size()), world(skeleton.joints.size());
  rest_local_transforms(skeleton, local);
  world_transforms(skeleton, local, world);
  return world;
}

}  // namespace

std::vector<glm::vec3> rest_joint_positions(const Skeleton& skeleton) {
  const std::vector<glm::mat4> world = rest_world(skeleton);
  std::vector<glm::vec3> positions;
  positions.reserve(world.size());
  for (const glm::mat4& m : world) positions.emplace_back(m[3]);
  return positions;
}

BodyMesh build_body_mesh(const Skeleton& skeleton, const BodyMeshParams& params) {
  if (params.grid_cells < 8 || params.grid_cells > 2048)
    throw std::invalid_argument("build_body_mesh: grid_cells must be 8 to 2048");
  if (!(params.output_scale > 0.0f) || !std::isfinite(params.output_scale))
    throw std::invalid_argument("build_body_mesh: output_scale must be positive");
  if (!(params.meters_per_unit > 0.0f) || !std::isfinite(params.meters_per_unit))
    throw std::invalid_argument("build_body_mesh: meters_per_unit must be positive");

  const std::vector<glm::mat4> world = rest_world(skeleton);
  std::vector<glm::vec3> joints;
  joints.reserve(world.size());
  for (const glm::mat4& m : world) joints.emplace_back(m[3]);

  BodyMesh body;
  BodyShape shape = body_shape(skeleton, joints, params.shape);
  if (shape.capsules.empty())
    throw std::invalid_argument("build_body_mesh: the skeleton has no bone of nonzero length");

  // The grid spans the capsules' bounds plus two cells, so its border samples are all outside and
  // the surface closes. The smooth union swells the body by at most blend / 4.
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const BoneCapsule& c : shape.capsules) {
    lo = glm::min(lo, glm::min(c.a - c.radius_a, c.b - c.radius_b));
    hi = glm::max(hi, glm::max(c.a + c.radius_a, c.b + c.radius_b));
  }
  const glm::vec3 extent = hi - lo;
  const float cell = std::max({extent.x, extent.y, extent.z}) / static_cast<float>(params.grid_cells);
  const glm::vec3 pad(2.0f * cell + 0.25f * shape.blend);
  // A gap narrower than the grid would fall between samples and close up again.
  if (shape.separation > 0.0f) shape.separation = std::max(shape.separation, 1.5f * cell);
  const ScalarGrid grid = sample_grid(
      lo - pad, hi + pad, cell, [&](const glm::vec3& p) { return body_field(shape, p); }, params.threads);
  body.cell = cell;

  body.mesh = marching_cubes(grid, 0.0f);
  taubin_smooth(body.mesh.positions, body.mesh.indices, params.smoothing, params.threads);
  body.mesh.normals.resize(body.mesh.positions.size());
  area_weighted_normals(body.mesh.positions, body.mesh.indices, body.mesh.normals);
  for (std::size_t v = 0; v < body.mesh.normals.size(); ++v)
    if (body.mesh.normals[v] == glm::vec3(0.0f))
      body.mesh.normals[v] = field_normal(shape, body.mesh.positions[v], 0.5f * cell);
  body.output_scale = params.output_scale;
  if (params.output_scale != 1.0f)
    for (glm::vec3& p : body.mesh.positions) p *= params.output_scale;

  body.shape = std::move(shape);
  if (!params.shape.exclude_from.empty()) body.attach_joint = find_joint(skeleton, params.shape.exclude_from);
  if (body.attach_joint >= 0) {
    body.attach_rest_world = world[static_cast<std::size_t>(body.attach_joint)];
    body.attach_rest_world[3] = glm::vec4(glm::vec3(body.attach_rest_world[3]) * params.output_scale, 1.0f);
    body.head_placement = glm::scale(body.attach_rest_world, glm::vec3(params.output_scale / params.meters_per_unit));
  }
  return body;
}

}  // namespace performer
