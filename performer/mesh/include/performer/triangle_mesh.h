// An indexed triangle mesh as plain streams: the layout a vertex buffer, an index buffer and the
// skinning job (skinning.h) take directly, so a mesh moves between generator, loader, skinning and
// exporter without conversion.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace performer {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // one per position, unit length; may be empty
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
};

}  // namespace performer
