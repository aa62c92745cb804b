// Writing a mesh (a deformed face, a skinned body) for viewers and other tools: binary PLY, which
// is compact and exact (the floats are stored as they are), and Wavefront OBJ, which every 3D
// program reads. Both are written atomically: the file is either complete or untouched.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

#include <glm/vec3.hpp>

namespace performer {

// Views of the streams to write, owning nothing.
struct MeshView {
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;      // empty: no normals written
  std::span<const std::uint32_t> indices;  // triangles, counter-clockwise from outside
};

// Binary little-endian PLY (whatever the host's byte order): vertex x y z [nx ny nz] as float,
// faces as "list uchar uint vertex_indices".
void write_ply(const std::filesystem::path& path, const MeshView& mesh);

// OBJ: "v", "vn" (when normals are given, index-matched to the vertices) and "f a//a b//b c//c"
// lines, numbers written with enough digits to read back the same floats, independent of locale.
void write_obj(const std::filesystem::path& path, const MeshView& mesh);

// Both throw std::invalid_argument "PATH: problem" for an inconsistent mesh (normals not matching
// the positions, index count not a multiple of 3, an index past the vertices) before touching the
// file, and std::runtime_error "PATH: problem" when the file cannot be written.

}  // namespace performer
