#include "wavelet_apps/control_net.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "dwt/error.h"
#include "imageio/atomic_write.h"
#include "wavelet_apps/error.h"

// The performer's procedural head (the built-in control net) and mesh writers, when it is built
// (GPUJ2K_BUILD_PERFORMER): see CMakeLists.txt.
#ifdef GPUJ2K_WAVELET_APPS_WITH_PERFORMER
#include <glm/vec3.hpp>

#include "performer/mesh_io.h"
#include "performer/procedural_head.h"
#endif

namespace wavelet_apps {

namespace {

[[noreturn]] void fail_at(const std::filesystem::path& path, int line, const std::string& problem) {
  throw AppError(path.string() + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + problem);
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool parse_float(const std::string& s, float& value) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size() && std::isfinite(value);
}

// "ROWS COLUMNS [wrap] [capped]" starting at words[first].
void parse_grid_header(const std::filesystem::path& path, int line, const std::vector<std::string>& w,
                       std::size_t first, ControlNet& net) {
  constexpr int kMaxSide = 1 << 14;
  auto side = [&](std::size_t i, const char* what) {
    int v = 0;
    const auto [end, ec] = std::from_chars(w[i].data(), w[i].data() + w[i].size(), v);
    if (ec != std::errc() || end != w[i].data() + w[i].size() || v < 1 || v > kMaxSide)
      fail_at(path, line,
              std::string(what) + " '" + w[i] + "' is not a whole number in 1.." + std::to_string(kMaxSide));
    return v;
  };
  if (w.size() < first + 2) fail_at(path, line, "expected ROWS COLUMNS [wrap] [capped]");
  net.rows = side(first, "rows");
  net.columns = side(first + 1, "columns");
  for (std::size_t i = first + 2; i < w.size(); ++i) {
    if (w[i] == "wrap")
      net.wrap = true;
    else if (w[i] == "capped")
      net.capped = true;
    else
      fail_at(path, line, "unknown grid flag '" + w[i] + "' (expected wrap or capped)");
  }
}

void read_point(const std::filesystem::path& path, int line, const std::vector<std::string>& w, ControlNet& net) {
  Point3 p{};
  if (w.size() < 3) fail_at(path, line, "expected three coordinates x y z");
  for (std::size_t i = 0; i < 3; ++i)
    if (!parse_float(w[i], p[i])) fail_at(path, line, "'" + w[i] + "' is not a finite number");
  net.points.push_back(p);
}

ControlNet read_text_net(const std::filesystem::path& path, std::istream& in) {
  ControlNet net;
  bool header = false;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const auto w = words(line);
    if (w.empty()) continue;
    if (!header) {
      if (w[0] != "controlnet") fail_at(path, line_number, "expected 'controlnet ROWS COLUMNS [wrap] [capped]'");
      parse_grid_header(path, line_number, w, 1, net);
      header = true;
      continue;
    }
    if (w.size() != 3) fail_at(path, line_number, "expected three coordinates x y z");
    if (net.points.size() == static_cast<std::size_t>(net.rows) * static_cast<std::size_t>(net.columns))
      fail_at(path, line_number, "more points than ROWS * COLUMNS");
    read_point(path, line_number, w, net);
  }
  if (!header) fail_at(path, 0, "empty control net (no 'controlnet ROWS COLUMNS' line)");
  return net;
}

ControlNet read_ply_net(const std::filesystem::path& path, std::istream& in) {
  ControlNet net;
  bool grid = false, ascii = false;
  long long vertices = -1;
  int line_number = 0;
  std::string line;
  std::getline(in, line);
  ++line_number;
  for (; std::getline(in, line);) {
    ++line_number;
    const auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") ascii = w.size() >= 2 && w[1] == "ascii";
    if (w[0] == "comment" && w.size() >= 2 && w[1] == "grid") {
      parse_grid_header(path, line_number, w, 2, net);
      grid = true;
    }
    if (w[0] == "element" && w.size() == 3 && w[1] == "vertex") vertices = std::atoll(w[2].c_str());
  }
  if (!ascii) fail_at(path, 0, "only ASCII PLY control nets are read (format ascii 1.0)");
  if (!grid) fail_at(path, 0, "no 'comment grid ROWS COLUMNS' line in the PLY header");
  if (vertices != static_cast<long long>(net.rows) * net.columns)
    fail_at(path, 0, "the vertex count is not ROWS * COLUMNS of the grid comment");
  for (long long v = 0; v < vertices && std::getline(in, line); ++v) {
    ++line_number;
    read_point(path, line_number, words(line), net);
  }
  return net;
}

#ifdef GPUJ2K_WAVELET_APPS_WITH_PERFORMER
glm::vec3 to_glm(const Point3& p) { return {p[0], p[1], p[2]}; }
#endif

// One output sample of an axis as weights on net indices.
struct Tap {
  int index;
  float weight;
};
using AxisSample = std::vector<Tap>;

// Uniform cubic B-spline samples along an axis of n points, `s` per cell; open ends are extended by
// reflection (P(-1) = 2 P(0) - P(1)), so the curve starts and ends at the end points.
std::vector<AxisSample> axis_samples(int n, bool wrap, int s) {
  std::vector<AxisSample> out;
  if (s == 1 || n < 2) {
    for (int i = 0; i < n; ++i) out.push_back({{i, 1.0f}});
    return out;
  }
  const int count = wrap ? n * s : (n - 1) * s + 1;
  for (int k = 0; k < count; ++k) {
    const int cell = std::min(k / s, wrap ? n - 1 : n - 2);
    const float t = static_cast<float>(k - cell * s) / static_cast<float>(s);
    const float b[4] = {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6,
                        (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
    AxisSample sample;
    for (int j = 0; j < 4; ++j) {
      const int i = cell - 1 + j;
      if (wrap)
        sample.push_back({((i % n) + n) % n, b[j]});
      else if (i < 0)
        sample.insert(sample.end(), {{0, 2 * b[j]}, {1, -b[j]}});
      else if (i >= n)
        sample.insert(sample.end(), {{n - 1, 2 * b[j]}, {n - 2, -b[j]}});
      else
        sample.push_back({i, b[j]});
    }
    out.push_back(std::move(sample));
  }
  return out;
}

double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const Point3& a = m.positions[m.indices[t]];
    const Point3& b = m.positions[m.indices[t + 1]];
    const Point3& c = m.positions[m.indices[t + 2]];
    v += double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
         double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
         double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0]);
  }
  return v / 6;
}

}  // namespace

ControlNet read_control_net(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail_at(path, 0, "cannot open the control net");
  std::string first;
  std::getline(in, first);
  in.seekg(0);
  ControlNet net = first.rfind("ply", 0) == 0 ? read_ply_net(path, in) : read_text_net(path, in);
  if (net.points.size() != static_cast<std::size_t>(net.rows) * static_cast<std::size_t>(net.columns))
    fail_at(path, 0,
            "has " + std::to_string(net.points.size()) + " points, ROWS * COLUMNS is " +
                std::to_string(static_cast<long long>(net.rows) * net.columns));
  return net;
}

namespace {

std::string grid_words(const ControlNet& net) {
  return std::to_string(net.rows) + " " + std::to_string(net.columns) + (net.wrap ? " wrap" : "") +
         (net.capped ? " capped" : "");
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  imageio::write_bytes_atomically(path.string(),
                                  std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void append_point(std::string& out, const Point3& p) {
  char buf[96];
  // %.9g round-trips a float exactly.
  std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", double(p[0]), double(p[1]), double(p[2]));
  out += buf;
}

}  // namespace

void write_control_net_text(const std::filesystem::path& path, const ControlNet& net) {
  std::string out = "# gpuj2k control net: rows of points, x y z each\ncontrolnet " + grid_words(net) + "\n";
  for (const Point3& p : net.points) append_point(out, p);
  write_text_atomically(path, out);
}

void write_control_net_ply(const std::filesystem::path& path, const ControlNet& net) {
  const int quad_columns = net.wrap ? net.columns : net.columns - 1;
  const long long quads = static_cast<long long>(net.rows - 1) * std::max(quad_columns, 0);
  std::string out = "ply\nformat ascii 1.0\ncomment gpuj2k control net\ncomment grid " + grid_words(net) +
                    "\nelement vertex " + std::to_string(net.points.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(quads) +
                    "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (const Point3& p : net.points) append_point(out, p);
  for (int r = 0; r + 1 < net.rows; ++r)
    for (int c = 0; c < quad_columns; ++c) {
      const int c1 = (c + 1) % net.columns;
      out += "4 " + std::to_string(r * net.columns + c) + " " + std::to_string(r * net.columns + c1) + " " +
             std::to_string((r + 1) * net.columns + c1) + " " + std::to_string((r + 1) * net.columns + c) + "\n";
    }
  write_text_atomically(path, out);
}

std::vector<std::string> axis_names() { return {"X", "Y", "Z"}; }

ControlNet deform_net(const ControlNet& net, const dwt::DwtParams& params, std::span<const ScaleSpec> bands,
                      WaveletEngine& engine) {
  try {
    dwt::validate(params, net.columns, net.rows);
  } catch (const dwt::DwtError& e) {
    throw AppError("control net of " + std::to_string(net.rows) + " rows and " + std::to_string(net.columns) +
                   " columns: " + e.what());
  }
  ControlNet out = net;
  const std::size_t n = net.points.size();
  std::vector<float> plane(n);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < n; ++i) plane[i] = net.points[i][axis];
    const auto ops = scale_operations(bands, static_cast<int>(axis), net.columns, net.rows, params);
    engine.process(dwt::make_span(plane.data(), net.columns, net.rows), {}, params, ops);
    for (std::size_t i = 0; i < n; ++i) out.points[i][axis] = plane[i];
  }
  return out;
}

SurfaceMesh tessellate(const ControlNet& net, int subdivisions) {
  if (subdivisions < 1 || subdivisions > 64) throw AppError("subdivisions must be 1..64");
  const auto along_rows = axis_samples(net.rows, false, subdivisions);
  const auto along_columns = axis_samples(net.columns, net.wrap, subdivisions);
  const int R = static_cast<int>(along_rows.size()), C = static_cast<int>(along_columns.size());
  SurfaceMesh mesh;
  mesh.positions.reserve(static_cast<std::size_t>(R) * static_cast<std::size_t>(C) + 2);
  for (const AxisSample& rs : along_rows)
    for (const AxisSample& cs : along_columns) {
      double p[3] = {0, 0, 0};
      for (const Tap& r : rs)
        for (const Tap& c : cs) {
          const Point3& q = net.at(r.index, c.index);
          for (int a = 0; a < 3; ++a) p[a] += double(r.weight) * c.weight * q[static_cast<std::size_t>(a)];
        }
      mesh.positions.push_back({float(p[0]), float(p[1]), float(p[2])});
    }
  auto vertex = [&](int r, int c) { return static_cast<std::uint32_t>(r * C + (c % C)); };
  const int quad_columns = net.wrap ? C : C - 1;
  for (int r = 0; r + 1 < R; ++r)
    for (int c = 0; c < quad_columns; ++c) {
      const std::uint32_t a = vertex(r, c), b = vertex(r, c + 1), d = vertex(r + 1, c), e = vertex(r + 1, c + 1);
      mesh.indices.insert(mesh.indices.end(), {a, d, e, a, e, b});
    }
  if (net.capped && C >= 3) {
    for (const int r : {0, R - 1}) {
      Point3 centre{0, 0, 0};
      for (int c = 0; c < C; ++c)
        for (std::size_t a = 0; a < 3; ++a) centre[a] += mesh.positions[vertex(r, c)][a] / static_cast<float>(C);
      const auto centre_index = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(centre);
      for (int c = 0; c < quad_columns; ++c) {
        if (r == 0)
          mesh.indices.insert(mesh.indices.end(), {centre_index, vertex(r, c), vertex(r, c + 1)});
        else
          mesh.indices.insert(mesh.indices.end(), {centre_index, vertex(r, c + 1), vertex(r, c)});
      }
    }
  }
  // A closed surface faces outward when its signed volume is positive.
  if (net.wrap && net.capped && signed_volume(mesh) < 0)
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  return mesh;
}

std::string mesh_problem(const SurfaceMesh& mesh) {
  if (mesh.indices.size() % 3 != 0) return "index count is not a multiple of 3";
  if (mesh.indices.empty()) return "no triangles";
  for (const Point3& p : mesh.positions)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return "a coordinate is not finite";
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a >= mesh.positions.size() || b >= mesh.positions.size() || c >= mesh.positions.size())
      return "triangle " + std::to_string(t / 3) + " names a vertex past the end";
    if (a == b || b == c || a == c) return "triangle " + std::to_string(t / 3) + " repeats a vertex";
  }
  return {};
}

#ifdef GPUJ2K_WAVELET_APPS_WITH_PERFORMER
void write_mesh(const std::filesystem::path& path, const SurfaceMesh& mesh) {
  std::vector<glm::vec3> positions;
  positions.reserve(mesh.positions.size());
  for (const Point3& p : mesh.positions) positions.push_back(to_glm(p));
  const performer::MeshView view{positions, {}, mesh.indices};
  const std::string ext = path.extension().string();
  if (ext == ".obj" || ext == ".OBJ")
    performer::write_obj(path, view);
  else if (ext == ".ply" || ext == ".PLY")
    performer::write_ply(path, view);
  else
    throw AppError(path.string() + ": a surface mesh is written as .obj or .ply");
}

ControlNet head_control_net(int rings, int segments) {
  performer::HeadParams params;
  params.rings = rings;
  params.segments = segments;
  const performer::FaceModel head = performer::build_procedural_head(performer::VisemeSet{}, params);
  // Vertex 0 is the crown pole, then rows of `segments` vertices, then the neck's pole.
  const std::size_t grid_vertices = head.positions.size() - 2;
  ControlNet net;
  net.columns = segments;
  net.rows = static_cast<int>(grid_vertices / static_cast<std::size_t>(segments));
  net.wrap = true;
  net.capped = true;
  net.points.reserve(grid_vertices);
  for (int r = 0; r < net.rows; ++r)
    for (int c = 0; c < segments; ++c) {
      // Column 0 faces forward; starting half-way round puts the wrap seam at the back.
      const int source = (c + segments / 2) % segments;
      const glm::vec3& p = head.positions[1 + static_cast<std::size_t>(r) * static_cast<std::size_t>(segments) +
                                          static_cast<std::size_t>(source)];
      net.points.push_back({p.x, p.y, p.z});
    }
  return net;
}
#else
void write_mesh(const std::filesystem::path& path, const SurfaceMesh&) {
  throw AppError(
      path.string() +
      ": writing surface meshes needs the performer's mesh writers (configure with GPUJ2K_BUILD_PERFORMER=ON)");
}

ControlNet head_control_net(int, int) {
  throw AppError("the built-in head is the performer's procedural head (configure with GPUJ2K_BUILD_PERFORMER=ON)");
}
#endif

}  // namespace wavelet_apps
