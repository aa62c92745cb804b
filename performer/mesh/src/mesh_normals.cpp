#include "performer/mesh_normals.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace performer {

void area_weighted_normals(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                           std::span<glm::vec3> out) {
  if (out.size() != positions.size())
    throw std::invalid_argument("area_weighted_normals: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(positions.size()) + " vertices");
  if (indices.size() % 3 != 0) throw std::invalid_argument("area_weighted_normals: index count is not a multiple of 3");
  for (const std::uint32_t i : indices)
    if (i >= positions.size())
      throw std::invalid_argument("area_weighted_normals: index " + std::to_string(i) + " out of range for " +
                                  std::to_string(positions.size()) + " vertices");
  for (glm::vec3& n : out) n = glm::vec3(0.0f);
  // The cross product of two edges is twice the triangle's area times its unit normal: summing it
  // is the area weighting.
  for (std::size_t t = 0; t < indices.size(); t += 3) {
    const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    out[indices[t]] += n;
    out[indices[t + 1]] += n;
    out[indices[t + 2]] += n;
  }
  for (glm::vec3& n : out) {
    const float length = glm::length(n);
    n = length > 1e-30f && std::isfinite(length) ? n / length : glm::vec3(0.0f);
  }
}

}  // namespace performer
