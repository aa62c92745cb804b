// Vertex normals of a triangle mesh, each the area-weighted average of the normals of the triangles
// around it: large triangles, which describe more of the surface, count more than slivers.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace performer {

// out[v]: unit normal of vertex v, facing the side triangles wind counter-clockwise around; the zero
// vector where the triangles around v have no area (or v is in none), so the caller can pick
// another source. Throws std::invalid_argument on size mismatches or indices out of range.
void area_weighted_normals(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                           std::span<glm::vec3> out);

}  // namespace performer
