// Tests for the face side of the performer (thesis 3.4.1, 3.4.4-3.4.5): the procedural head and
// its viseme and expression deformation vectors (equation 3.5), the per-frame blend of equation 3.9
// with normals by 3.11, channel binding from weight tracks, the PLY and OBJ writers, and glTF
// avatars with Oculus- and ARKit-named morph targets (fixtures are written by write_gltf_face, so no
// downloaded asset is needed).

#include <gtest/gtest.h>

#include "support/scratch_dir.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "performer/face_deform.h"
#include "performer/face_model.h"
#include "performer/gltf_face.h"
#include "performer/gltf_skin.h"
#include "performer/mesh_io.h"
#include "performer/morph_mapping.h"
#include "performer/procedural_head.h"
#include "performer/viseme_error.h"
#include "performer/viseme_library.h"
#include "performer/weights_track.h"

using performer::FaceDeformJob;
using performer::FaceModel;
using performer::FaceStreams;
using performer::MorphTarget;

namespace {

const performer::VisemeSet& viseme_set() {
  static const performer::VisemeSet set = performer::load_viseme_set(performer::default_viseme_dir() / "visemes.tsv");
  return set;
}

// The default head, built once: the tests only read it.
const FaceModel& head() {
  static const FaceModel model = performer::build_procedural_head(viseme_set());
  return model;
}

// A coarse head for the file round trips, which only need some mesh with targets.
const FaceModel& small_head() {
  static const FaceModel model = [] {
    performer::HeadParams p;
    p.rings = 40;
    p.segments = 48;
    return performer::build_procedural_head(viseme_set(), p);
  }();
  return model;
}

const MorphTarget& target(const FaceModel& m, const std::string& name) {
  const MorphTarget* t = m.target(name);
  if (!t) throw std::runtime_error("no target " + name);
  return *t;
}

float max_delta(const MorphTarget& t) {
  float most = 0.0f;
  for (const glm::vec3& d : t.position_deltas) most = std::max(most, glm::length(d));
  return most;
}

bool same_bits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// One blend of the model with these weights, serial or threaded.
struct Blend {
  std::vector<glm::vec3> positions, normals;
};
Blend blend(const FaceModel& m, const std::vector<float>& weights, unsigned threads = 1) {
  Blend out{std::vector<glm::vec3>(m.vertex_count()), std::vector<glm::vec3>(m.vertex_count())};
  const FaceStreams streams(m);
  const FaceDeformJob job{m.positions, m.normals,     streams.positions, streams.normals,
                          weights,     out.positions, out.normals};
  if (threads == 1)
    performer::deform_face(job);
  else
    performer::deform_face_parallel(job, threads);
  return out;
}

// ---------------------------------------------------------------- the procedural head

TEST(ProceduralHead, IsClosedAndConsistentlyOriented) {
  const FaceModel& m = head();
  ASSERT_NO_THROW(performer::validate_face_model(m, "head"));
  // Every directed edge once and its reverse once: each undirected edge is shared by exactly two
  // triangles that traverse it in opposite directions (closed, manifold, consistently wound).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
      ASSERT_NE(a, b) << "triangle " << t / 3 << " repeats a vertex";
      ++directed[{a, b}];
    }
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "edge " << edge.first << "-" << edge.second << " is open";
  }
  // Outward: the signed volume (divergence theorem) is positive, and about a head's (3-5 litres).
  double volume = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  EXPECT_GT(volume, 0.003);
  EXPECT_LT(volume, 0.006);
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
  // Normals point out: on average away from the head's centre.
  double outward = 0.0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    outward += glm::dot(m.normals[v], glm::normalize(m.positions[v] - glm::vec3(0.0f, 0.05f, 0.0f)));
  EXPECT_GT(outward / static_cast<double>(m.vertex_count()), 0.8);
}

TEST(ProceduralHead, SizeOriginAndResolution) {
  const FaceModel& m = head();
  EXPECT_GE(m.vertex_count(), 3000u);
  EXPECT_LE(m.vertex_count(), 12000u);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : m.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // Crown at +0.165 m, neck stub to -0.11 m, face toward +Z (nose tip the front), mirror-symmetric.
  EXPECT_NEAR(hi.y, 0.165f, 0.005f);
  EXPECT_NEAR(lo.y, -0.11f, 0.005f);
  EXPECT_GT(hi.z, 0.11f);
  EXPECT_LT(hi.z, 0.14f);
  EXPECT_NEAR(lo.x, -hi.x, 1e-6f);
  EXPECT_GT(hi.x, 0.07f);
  EXPECT_LT(hi.x, 0.09f);
  // The front-most point is the nose, on the midline between eyes and mouth.
  const auto nose = std::max_element(m.positions.begin(), m.positions.end(),
                                     [](const glm::vec3& a, const glm::vec3& b) { return a.z < b.z; });
  EXPECT_LT(std::abs(nose->x), 0.005f);
  EXPECT_GT(nose->y, 0.0f);
  EXPECT_LT(nose->y, 0.04f);
}

TEST(ProceduralHead, HasATargetForEveryVisemeAndExpression) {
  const FaceModel& m = head();
  const auto& set = viseme_set();
  ASSERT_EQ(m.targets.size(), set.visemes.size() + performer::kHeadExpressions.size());
  for (std::size_t i = 0; i < set.visemes.size(); ++i) EXPECT_EQ(m.targets[i].name, set.visemes[i].name);
  for (std::size_t i = 0; i < performer::kHeadExpressions.size(); ++i)
    EXPECT_EQ(m.targets[set.visemes.size() + i].name, performer::kHeadExpressions[i]);
  for (const MorphTarget& t : m.targets) {
    if (t.name == "closed") {
      // The neutral face is the closed mouth (3.4.1), so its DV is exactly zero.
      EXPECT_EQ(max_delta(t), 0.0f);
      continue;
    }
    EXPECT_GT(max_delta(t), 0.001f) << t.name << " barely moves";
    EXPECT_LT(max_delta(t), 0.05f) << t.name << " moves implausibly far";
    float normal_change = 0.0f;
    for (const glm::vec3& d : t.normal_deltas) normal_change = std::max(normal_change, glm::length(d));
    EXPECT_GT(normal_change, 0.01f) << t.name << " has no normal DV";
  }
}

// The front of the lower lip on the midline, in the neutral face.
std::size_t lower_lip_vertex(const FaceModel& m) {
  std::size_t best = 0;
  float best_z = -1.0f;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const glm::vec3 p = m.positions[v];
    if (std::abs(p.x) < 0.004f && p.y < -0.014f && p.y > -0.035f && p.z > best_z) best = v, best_z = p.z;
  }
  return best;
}

TEST(ProceduralHead, MouthOpenVisemesDropTheJaw) {
  const FaceModel& m = head();
  const std::size_t lip = lower_lip_vertex(m);
  ASSERT_GT(m.positions[lip].z, 0.09f);
  // The open-mouth visemes (Figure 3.5's AA, EH, O, NG, K) lower the lower lip with the jaw; AA the
  // most. Closed-mouth ones (M) do not.
  EXPECT_LT(target(m, "AA").position_deltas[lip].y, -0.008f);
  for (const char* name : {"EH", "O", "NG", "K"}) EXPECT_LT(target(m, name).position_deltas[lip].y, -0.003f) << name;
  for (const char* name : {"EH", "O", "NG", "K"})
    EXPECT_LT(target(m, "AA").position_deltas[lip].y, target(m, name).position_deltas[lip].y) << name;
  EXPECT_GT(target(m, "M").position_deltas[lip].y, -0.001f);
  // Rounded visemes pull the mouth corners in; spread ones push them out.
  std::size_t corner = 0;
  float best = 1.0f;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const glm::vec3 p = m.positions[v];
    const float d = std::abs(p.x - 0.024f) + std::abs(p.y + 0.012f) + 0.2f * std::abs(p.z - 0.1f);
    if (p.z > 0.07f && d < best) best = d, corner = v;
  }
  EXPECT_LT(target(m, "UH").position_deltas[corner].x, -0.003f);
  EXPECT_GT(target(m, "IY").position_deltas[corner].x, 0.001f);
  EXPECT_GT(target(m, "smile").position_deltas[corner].y, 0.003f);
}

TEST(ProceduralHead, BlinkBringsTheUpperLidDown) {
  const FaceModel& m = head();
  const MorphTarget& blink = target(m, "blink");
  // Upper lid skin just above each eye's opening (eyes at x = +-0.032, y = 0.060) travels down
  // most of the opening's height; the lower lid stays.
  for (const float side : {-1.0f, 1.0f}) {
    float upper_drop = 0.0f, lower_move = 0.0f;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      const glm::vec3 p = m.positions[v];
      if (p.z < 0.05f || std::abs(p.x - side * 0.032f) > 0.003f) continue;
      if (p.y > 0.0655f && p.y < 0.068f) upper_drop = std::min(upper_drop, blink.position_deltas[v].y);
      if (p.y < 0.0540f && p.y > 0.050f) lower_move = std::max(lower_move, std::abs(blink.position_deltas[v].y));
    }
    EXPECT_LT(upper_drop, -0.008f) << "side " << side;
    EXPECT_LT(lower_move, 0.001f) << "side " << side;
  }
  // Blinking moves nothing below the eyes or on the back of the head.
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    if (m.positions[v].y < 0.03f || m.positions[v].z < 0.0f) {
      ASSERT_EQ(blink.position_deltas[v], glm::vec3(0.0f));
    }
}

TEST(ProceduralHead, IsDeterministicAndChecksParameters) {
  performer::HeadParams p;
  p.rings = 30;
  p.segments = 32;
  const FaceModel a = performer::build_procedural_head(viseme_set(), p);
  const FaceModel b = performer::build_procedural_head(viseme_set(), p);
  EXPECT_TRUE(same_bits(a.positions, b.positions));
  EXPECT_EQ(a.indices, b.indices);
  for (std::size_t t = 0; t < a.targets.size(); ++t)
    EXPECT_TRUE(same_bits(a.targets[t].position_deltas, b.targets[t].position_deltas));
  p.segments = 33;
  EXPECT_THROW(performer::build_procedural_head(viseme_set(), p), std::invalid_argument);
  p.segments = 32;
  p.rings = 3;
  EXPECT_THROW(performer::build_procedural_head(viseme_set(), p), std::invalid_argument);
  // Scale multiplies positions and deltas alike.
  performer::HeadParams q;
  q.rings = 30;
  q.segments = 32;
  q.scale = 2.0f;
  const FaceModel c = performer::build_procedural_head(viseme_set(), q);
  EXPECT_FLOAT_EQ(c.positions[5].y, 2.0f * a.positions[5].y);
  EXPECT_FLOAT_EQ(c.targets[3].position_deltas[100].y, 2.0f * a.targets[3].position_deltas[100].y);
}

// ---------------------------------------------------------------- equations 3.9 and 3.11

TEST(FaceDeform, ZeroWeightsGiveTheNeutralFaceExactly) {
  const FaceModel& m = head();
  const Blend b = blend(m, std::vector<float>(m.targets.size(), 0.0f));
  EXPECT_TRUE(same_bits(b.positions, m.positions));
  EXPECT_TRUE(same_bits(b.normals, m.normals));
}

TEST(FaceDeform, WeightOneGivesTheTarget) {
  const FaceModel& m = head();
  for (const char* name : {"AA", "UH", "smile", "blink"}) {
    std::vector<float> w(m.targets.size(), 0.0f);
    const int t = m.find_target(name);
    ASSERT_GE(t, 0);
    w[static_cast<std::size_t>(t)] = 1.0f;
    const Blend b = blend(m, w);
    const MorphTarget& dv = m.targets[static_cast<std::size_t>(t)];
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      ASSERT_EQ(b.positions[v], m.positions[v] + dv.position_deltas[v]) << name << " vertex " << v;
      // The target's own normal (neutral + normal DV, unit up to rounding).
      const glm::vec3 expected = m.normals[v] + dv.normal_deltas[v];
      ASSERT_NEAR(glm::length(expected), 1.0f, 1e-5f);
      ASSERT_LT(glm::length(b.normals[v] - expected), 1e-5f) << name << " vertex " << v;
    }
  }
}

TEST(FaceDeform, NormalsStayUnitAndThreadsAgree) {
  const FaceModel& m = head();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> weight(-0.5f, 1.5f);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<float> w(m.targets.size());
    for (float& x : w) x = weight(rng);
    w[0] = 0.0f;
    const Blend serial = blend(m, w, 1);
    for (const glm::vec3& n : serial.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
    // Equation 3.9 is linear: the blend equals the neutral plus the weighted sum, to rounding.
    for (std::size_t v = 0; v < m.vertex_count(); v += 97) {
      glm::dvec3 expected(m.positions[v]);
      for (std::size_t t = 0; t < m.targets.size(); ++t)
        expected += double(w[t]) * glm::dvec3(m.targets[t].position_deltas[v]);
      ASSERT_LT(glm::length(expected - glm::dvec3(serial.positions[v])), 1e-6);
    }
    for (const unsigned threads : {2u, 3u, 8u}) {
      const Blend threaded = blend(m, w, threads);
      EXPECT_TRUE(same_bits(threaded.positions, serial.positions)) << threads << " threads";
      EXPECT_TRUE(same_bits(threaded.normals, serial.normals)) << threads << " threads";
    }
  }
}

TEST(FaceDeform, RejectsInconsistentJobsAndSkipsNormalsOnRequest) {
  const FaceModel& m = small_head();
  const FaceStreams streams(m);
  std::vector<float> w(m.targets.size(), 0.0f);
  std::vector<glm::vec3> p(m.vertex_count()), n(m.vertex_count());
  FaceDeformJob job{m.positions, m.normals, streams.positions, streams.normals, w, p, n};
  EXPECT_TRUE(job.valid());
  job.weights = std::span<const float>(w).first(w.size() - 1);
  EXPECT_THROW(performer::deform_face(job), std::invalid_argument);
  job.weights = w;
  job.out_positions = std::span<glm::vec3>(p).first(p.size() - 1);
  EXPECT_THROW(performer::deform_face_parallel(job), std::invalid_argument);
  // Positions only.
  const FaceDeformJob positions_only{m.positions, {}, streams.positions, {}, w, p, {}};
  EXPECT_NO_THROW(performer::deform_face(positions_only));
  EXPECT_TRUE(same_bits(p, m.positions));
}

TEST(FaceDeform, BindsTrackChannelsByName) {
  const FaceModel& m = small_head();
  performer::WeightTrack track;
  track.channels = {"closed", "AA", "O", "smile", "frown", "blink"};
  track.viseme_channels = 3;
  track.times = {0.0};
  track.values = {0.1f, 0.5f, 0.25f, 0.75f, 1.0f, 0.3f};
  const performer::ChannelBinding binding = performer::bind_channels(track, m);
  // "frown" names no target: ignored when weights are applied, and reported.
  ASSERT_EQ(binding.unmatched, std::vector<std::string>{"frown"});
  EXPECT_EQ(binding.target_of_channel[4], -1);
  std::vector<float> weights(m.targets.size(), -1.0f);
  performer::target_weights(binding, track.frame(0), weights);
  EXPECT_EQ(weights[static_cast<std::size_t>(m.find_target("AA"))], 0.5f);
  EXPECT_EQ(weights[static_cast<std::size_t>(m.find_target("O"))], 0.25f);
  EXPECT_EQ(weights[static_cast<std::size_t>(m.find_target("smile"))], 0.75f);
  EXPECT_EQ(weights[static_cast<std::size_t>(m.find_target("blink"))], 0.3f);
  EXPECT_EQ(weights[static_cast<std::size_t>(m.find_target("EH"))], 0.0f);
  EXPECT_THROW(performer::target_weights(binding, std::span<const float>(track.values).first(3), weights),
               std::invalid_argument);
}

// ---------------------------------------------------------------- PLY and OBJ

TEST(MeshIo, PlyAndObjReadBack) {
  const FaceModel& m = head();
  test_support::ScratchDir dir("performer_face");
  const performer::MeshView mesh{m.positions, m.normals, m.indices};
  const auto ply = dir / "head.ply", obj = dir / "head.obj";
  performer::write_ply(ply, mesh);
  performer::write_obj(obj, mesh);

  // PLY: header counts, then exactly the binary body they announce; the first vertex reads back.
  std::ifstream in(ply, std::ios::binary);
  std::string line, header;
  std::size_t vertices = 0, faces = 0;
  while (std::getline(in, line) && line != "end_header") {
    header += line + "\n";
    std::istringstream fields(line);
    std::string a, b;
    std::size_t count = 0;
    if (fields >> a >> b >> count && a == "element") (b == "vertex" ? vertices : faces) = count;
  }
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_EQ(vertices, m.vertex_count());
  EXPECT_EQ(faces, m.triangle_count());
  const auto body_start = static_cast<std::size_t>(in.tellg());
  EXPECT_EQ(std::filesystem::file_size(ply), body_start + vertices * 24 + faces * 13);
  float first[6];
  in.read(reinterpret_cast<char*>(first), sizeof first);
  EXPECT_EQ(first[0], m.positions[0].x);
  EXPECT_EQ(first[4], m.normals[0].y);
  in.seekg(static_cast<std::streamoff>(body_start + vertices * 24));
  unsigned char n = 0;
  std::uint32_t tri[3];
  in.read(reinterpret_cast<char*>(&n), 1);
  in.read(reinterpret_cast<char*>(tri), sizeof tri);
  EXPECT_EQ(n, 3);
  EXPECT_EQ(tri[2], m.indices[2]);

  // OBJ: one v and vn per vertex, one f per triangle, numbers exact.
  std::ifstream text(obj);
  std::size_t v = 0, vn = 0, f = 0;
  std::vector<glm::vec3> read_positions;
  while (std::getline(text, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      ++v;
      std::string x, y, z;
      fields >> x >> y >> z;
      read_positions.emplace_back(std::strtof(x.c_str(), nullptr), std::strtof(y.c_str(), nullptr),
                                  std::strtof(z.c_str(), nullptr));
    } else if (tag == "vn") {
      ++vn;
    } else if (tag == "f") {
      ++f;
      std::string corner;
      int corners = 0;
      while (fields >> corner) {
        ++corners;
        const auto slash = corner.find("//");
        ASSERT_NE(slash, std::string::npos);
        EXPECT_EQ(corner.substr(0, slash), corner.substr(slash + 2));
      }
      EXPECT_EQ(corners, 3);
    }
  }
  EXPECT_EQ(v, m.vertex_count());
  EXPECT_EQ(vn, m.vertex_count());
  EXPECT_EQ(f, m.triangle_count());
  EXPECT_TRUE(same_bits(read_positions, m.positions));
}

TEST(MeshIo, ErrorsNameTheFileAndLeaveNothingBehind) {
  test_support::ScratchDir dir("performer_face");
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> bad{0, 1, 3};
  const auto file = dir / "bad.ply";
  try {
    performer::write_ply(file, {p, {}, bad});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file));
  const auto nowhere = dir / "missing" / "head.obj";
  try {
    performer::write_obj(nowhere, {p, {}, std::vector<std::uint32_t>{0, 1, 2}});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(nowhere.string()), std::string::npos) << e.what();
  }
  // Nothing but the files written on purpose: no temporaries left.
  performer::write_obj(dir / "ok.obj", {p, {}, std::vector<std::uint32_t>{0, 1, 2}});
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);
}

// ---------------------------------------------------------------- glTF avatars

void expect_same_model(const FaceModel& a, const FaceModel& b) {
  EXPECT_TRUE(same_bits(a.positions, b.positions));
  EXPECT_TRUE(same_bits(a.normals, b.normals));
  EXPECT_EQ(a.indices, b.indices);
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t t = 0; t < a.targets.size(); ++t) {
    EXPECT_EQ(a.targets[t].name, b.targets[t].name);
    EXPECT_TRUE(same_bits(a.targets[t].position_deltas, b.targets[t].position_deltas)) << a.targets[t].name;
    EXPECT_TRUE(same_bits(a.targets[t].normal_deltas, b.targets[t].normal_deltas)) << a.targets[t].name;
  }
}

TEST(GltfFace, RoundTripsThroughGltfAndGlb) {
  const FaceModel& m = small_head();
  test_support::ScratchDir dir("performer_face");
  for (const char* name : {"head.gltf", "head.glb"}) {
    const auto file = dir / name;
    performer::write_gltf_face(file, m);
    const performer::GltfFace loaded = performer::load_gltf_face(file, viseme_set());
    EXPECT_TRUE(loaded.missing.empty());
    EXPECT_EQ(loaded.mesh, "face");
    expect_same_model(loaded.model, m);
    for (std::size_t t = 0; t < m.targets.size(); ++t) EXPECT_EQ(loaded.sources[t], m.targets[t].name);
  }
  // .glb really is binary glTF, .gltf JSON.
  std::ifstream glb(dir / "head.glb", std::ios::binary);
  char magic[4];
  glb.read(magic, 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");
  std::ifstream json(dir / "head.gltf");
  std::string first;
  json >> first;
  EXPECT_EQ(first.front(), '{');
}

// A copy of the small head whose targets carry other names, made from our targets.
FaceModel renamed(const std::vector<std::pair<std::string, MorphTarget>>& targets) {
  FaceModel m = small_head();
  m.targets.clear();
  for (auto [name, t] : targets) {
    t.name = name;
    m.targets.push_back(std::move(t));
  }
  return m;
}

// The part of a target on one side of the face (x > 0 is the head's left).
MorphTarget half(const MorphTarget& t, bool left) {
  MorphTarget h = t;
  const FaceModel& m = small_head();
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    if ((m.positions[v].x > 0.0f) != left) h.position_deltas[v] = h.normal_deltas[v] = glm::vec3(0.0f);
  return h;
}

TEST(GltfFace, MapsArkitBlendShapes) {
  const FaceModel& m = small_head();
  const MorphTarget &blink = target(m, "blink"), &smile = target(m, "smile"), &aa = target(m, "AA");
  const FaceModel arkit = renamed({{"eyeBlinkLeft", half(blink, true)},
                                   {"eyeBlinkRight", half(blink, false)},
                                   {"mouthSmileLeft", half(smile, true)},
                                   {"mouthSmileRight", half(smile, false)},
                                   {"jawOpen", aa}});
  test_support::ScratchDir dir("performer_face");
  const auto file = dir / "arkit.glb";
  performer::write_gltf_face(file, arkit);
  const performer::GltfFace loaded = performer::load_gltf_face(file, viseme_set());
  // blink = eyeBlinkLeft + eyeBlinkRight, which are the two halves of our blink: the whole of it.
  const MorphTarget* b = loaded.model.target("blink");
  ASSERT_NE(b, nullptr);
  EXPECT_TRUE(same_bits(b->position_deltas, blink.position_deltas));
  const MorphTarget* s = loaded.model.target("smile");
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(same_bits(s->position_deltas, smile.position_deltas));
  const std::size_t bi = static_cast<std::size_t>(loaded.model.find_target("blink"));
  EXPECT_NE(loaded.sources[bi].find("eyeBlinkLeft"), std::string::npos);
  EXPECT_NE(loaded.sources[bi].find("eyeBlinkRight"), std::string::npos);
  // AA has no Oculus morph here; the viseme_aa recipe builds it from jawOpen at 0.7.
  const MorphTarget* a = loaded.model.target("AA");
  ASSERT_NE(a, nullptr);
  for (std::size_t v = 0; v < m.vertex_count(); v += 31)
    EXPECT_NEAR(a->position_deltas[v].y, 0.7f * aa.position_deltas[v].y, 1e-7f);
  // What no ingredient supplies is reported missing, not invented.
  for (const char* name : {"worry", "anger", "M", "F"})
    EXPECT_NE(std::find(loaded.missing.begin(), loaded.missing.end(), name), loaded.missing.end()) << name;
  // closed is the neutral face: a zero DV.
  const MorphTarget* closed = loaded.model.target("closed");
  ASSERT_NE(closed, nullptr);
  for (const glm::vec3& d : closed->position_deltas) ASSERT_EQ(d, glm::vec3(0.0f));
  // A further expression added to the recipes is picked up too (and nothing is missing for it).
  const performer::MorphMapping extended = performer::parse_morph_recipes(
      "yawn\t1\tjawOpen\n", "extra.tsv", performer::load_morph_mapping(performer::default_morph_dir()));
  const performer::GltfFace with_yawn = performer::load_gltf_face(file, viseme_set(), extended);
  ASSERT_NE(with_yawn.model.target("yawn"), nullptr);
  EXPECT_TRUE(same_bits(with_yawn.model.target("yawn")->position_deltas, aa.position_deltas));
  EXPECT_EQ(with_yawn.missing, loaded.missing);
  // require_all turns the gaps into an error that lists them.
  try {
    performer::GltfFaceOptions options;
    options.require_all = true;
    performer::load_gltf_face(file, viseme_set(), options);
    FAIL() << "expected an error";
  } catch (const performer::GltfError& e) {
    EXPECT_NE(std::string(e.what()).find("worry"), std::string::npos) << e.what();
  }
}

TEST(GltfFace, MapsOculusVisemesThroughTheVisemeTable) {
  const FaceModel& m = small_head();
  // Ready Player Me spells the ih viseme "viseme_I"; case differences are forgiven.
  const FaceModel oculus = renamed({{"viseme_aa", target(m, "AA")},
                                    {"viseme_I", target(m, "IY")},
                                    {"VISEME_PP", target(m, "M")},
                                    {"viseme_sil", target(m, "closed")}});
  test_support::ScratchDir dir("performer_face");
  const auto file = dir / "oculus.gltf";
  performer::write_gltf_face(file, oculus);
  const performer::GltfFace loaded = performer::load_gltf_face(file, viseme_set());
  EXPECT_TRUE(same_bits(target(loaded.model, "AA").position_deltas, target(m, "AA").position_deltas));
  // IY and Y both map to Oculus ih (visemes.tsv).
  EXPECT_TRUE(same_bits(target(loaded.model, "IY").position_deltas, target(m, "IY").position_deltas));
  EXPECT_TRUE(same_bits(target(loaded.model, "Y").position_deltas, target(m, "IY").position_deltas));
  EXPECT_TRUE(same_bits(target(loaded.model, "M").position_deltas, target(m, "M").position_deltas));
  EXPECT_EQ(loaded.sources[static_cast<std::size_t>(loaded.model.find_target("M"))], "VISEME_PP");
  EXPECT_EQ(loaded.model.target("blink"), nullptr);
  EXPECT_NE(std::find(loaded.missing.begin(), loaded.missing.end(), "blink"), loaded.missing.end());
}

TEST(GltfFace, FileWithoutNeededMorphsIsAnErrorNamingIt) {
  const FaceModel& m = small_head();
  test_support::ScratchDir dir("performer_face");
  const auto file = dir / "robot.glb";
  performer::write_gltf_face(file, renamed({{"antennaUp", target(m, "AA")}, {"visorOpen", target(m, "blink")}}));
  try {
    performer::load_gltf_face(file, viseme_set());
    FAIL() << "expected an error";
  } catch (const performer::GltfError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find("none of the morph targets"), std::string::npos) << what;
    EXPECT_NE(what.find("blink"), std::string::npos) << what;      // what is missing
    EXPECT_NE(what.find("antennaUp"), std::string::npos) << what;  // what the file has
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  // A mesh with no morph targets at all.
  const auto plain = dir / "plain.gltf";
  performer::write_gltf_face(plain, renamed({}));
  EXPECT_THROW(performer::load_gltf_face(plain, viseme_set()), performer::GltfError);
  // A named mesh that is not there.
  performer::GltfFaceOptions options;
  options.mesh = "Wolf3D_Head";
  EXPECT_THROW(performer::load_gltf_face(file, viseme_set(), options), performer::GltfError);
}

TEST(GltfFace, MalformedFilesGiveErrors) {
  test_support::ScratchDir dir("performer_face");
  const auto json = dir / "broken.gltf";
  std::ofstream(json) << "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {";
  const auto glb = dir / "broken.glb";
  std::ofstream(glb, std::ios::binary) << "glTF\x02\x00\x00\x00garbage";
  const auto missing = dir / "absent.glb";
  for (const auto& file : {json, glb, missing}) {
    try {
      performer::load_gltf_face(file, viseme_set());
      FAIL() << "expected an error for " << file;
    } catch (const performer::GltfError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  // Writing: a folder that does not exist.
  EXPECT_THROW(performer::write_gltf_face(dir / "nowhere" / "x.glb", small_head()), std::runtime_error);
  FaceModel invalid = small_head();
  invalid.indices.push_back(0);
  EXPECT_THROW(performer::write_gltf_face(dir / "invalid.glb", invalid), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "invalid.glb"));
}

TEST(MorphMapping, DefaultFilesParseAndErrorsNameFileAndLine) {
  const performer::MorphMapping mapping = performer::load_morph_mapping(performer::default_morph_dir());
  EXPECT_EQ(mapping.oculus.size(), performer::kOculusVisemes.size());
  EXPECT_EQ(mapping.oculus_morphs("ih"), (std::vector<std::string>{"viseme_ih", "viseme_I"}));
  ASSERT_NE(mapping.recipe("blink"), nullptr);
  EXPECT_EQ(mapping.recipe("blink")->ingredients.size(), 2u);
  for (const char* e : {"smile", "worry", "surprise", "anger", "blink"}) EXPECT_NE(mapping.recipe(e), nullptr) << e;
  try {
    performer::parse_oculus_morphs("aa\tviseme_aa\nxx\tviseme_xx\n", "o.tsv");
    FAIL() << "expected an error";
  } catch (const performer::VisemeDataError& e) {
    EXPECT_EQ(e.file(), "o.tsv");
    EXPECT_EQ(e.line(), 2);
  }
  EXPECT_THROW(performer::parse_morph_recipes("smile\tmuch\tmouthSmileLeft\n", "a.tsv"), performer::VisemeDataError);
  EXPECT_THROW(performer::parse_morph_recipes("smile 1 a\nblink 1 b\nsmile 1 c\n", "a.tsv"),
               performer::VisemeDataError);
}

}  // namespace
