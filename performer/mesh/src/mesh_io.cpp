#include "performer/mesh_io.h"

#include <bit>
#include <charconv>
#include <cstring>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "performer/detail/atomic_file.h"

namespace performer {

namespace {

void check_mesh(const std::filesystem::path& path, const MeshView& mesh) {
  auto fail = [&path](const std::string& problem) { throw std::invalid_argument(path.string() + ": " + problem); };
  const std::size_t n = mesh.positions.size();
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    fail(std::to_string(n) + " positions but " + std::to_string(mesh.normals.size()) + " normals");
  if (mesh.indices.size() % 3 != 0)
    fail("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  for (const std::uint32_t i : mesh.indices)
    if (i >= n) fail("triangle index " + std::to_string(i) + " past the " + std::to_string(n) + " vertices");
}

// Appends a value's bytes in little-endian order: PLY says which order it uses, and little-endian
// is what nearly every reader expects.
template <typename T>
void put_le(std::vector<char>& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

// Shortest text that reads back as the same float (std::to_chars round-trips), so OBJ is lossless.
void put_float(std::string& out, float v) {
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, result.ptr);
}

}  // namespace

void write_ply(const std::filesystem::path& path, const MeshView& mesh) {
  check_mesh(path, mesh);
  const bool normals = !mesh.normals.empty();
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment gpuj2k performer\n";
  header += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  header += "property float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  header += "element face " + std::to_string(mesh.indices.size() / 3) + "\n";
  header += "property list uchar uint vertex_indices\nend_header\n";

  std::vector<char> body;
  body.reserve(mesh.positions.size() * (normals ? 24 : 12) + mesh.indices.size() / 3 * 13);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    put_le(body, p.x);
    put_le(body, p.y);
    put_le(body, p.z);
    if (!normals) continue;
    const glm::vec3 n = mesh.normals[v];
    put_le(body, n.x);
    put_le(body, n.y);
    put_le(body, n.z);
  }
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    put_le(body, std::uint8_t{3});
    put_le(body, mesh.indices[t]);
    put_le(body, mesh.indices[t + 1]);
    put_le(body, mesh.indices[t + 2]);
  }
  detail::write_file_atomically(path, [&](std::ostream& out) {
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
  });
}

void write_obj(const std::filesystem::path& path, const MeshView& mesh) {
  check_mesh(path, mesh);
  const bool normals = !mesh.normals.empty();
  std::string text = "# gpuj2k performer\n";
  text.reserve(mesh.positions.size() * (normals ? 80 : 40) + mesh.indices.size() * 12);
  auto put_vec = [&text](const char* tag, glm::vec3 v) {
    text += tag;
    for (const float c : {v.x, v.y, v.z}) {
      text += ' ';
      put_float(text, c);
    }
    text += '\n';
  };
  for (const glm::vec3& p : mesh.positions) put_vec("v", p);
  if (normals)
    for (const glm::vec3& n : mesh.normals) put_vec("vn", n);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    text += 'f';
    for (std::size_t k = 0; k < 3; ++k) {
      // OBJ indices are 1-based; vertex and normal share an index because they are per vertex.
      const std::string i = std::to_string(static_cast<std::uint64_t>(mesh.indices[t + k]) + 1);
      text += ' ';
      text += i;
      if (normals) text += "//" + i;
    }
    text += '\n';
  }
  detail::write_file_atomically(
      path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

}  // namespace performer
