// Unit vertex normals for face models, the neutral mesh's and each target's. Not public API: shared
// by the procedural head and the glTF face reader.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "performer/mesh_normals.h"

namespace performer::detail {

// area_weighted_normals(), with the zero vector it leaves where no triangle has area (a fully
// closed eyelid squeezes a strip of triangles flat) replaced by fallback[v], or by +Z when fallback
// is empty: normal DVs and the blend of equation 3.11 need a unit normal everywhere.
inline void unit_vertex_normals(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                std::span<const glm::vec3> fallback, std::span<glm::vec3> out) {
  area_weighted_normals(positions, indices, out);
  for (std::size_t v = 0; v < out.size(); ++v)
    if (out[v] == glm::vec3(0.0f)) out[v] = fallback.empty() ? glm::vec3(0.0f, 0.0f, 1.0f) : fallback[v];
}

}  // namespace performer::detail
