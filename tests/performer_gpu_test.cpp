// Equation 3.20 on the GPU (performer/render/gpu_deformer.h) against the CPU jobs it mirrors
// (character_deform.h): on the three CMU clips at several frames with speech driving the face, the
// deformed positions and normals agree within 1e-5 of the character's size. Runs on whatever context
// the GL layer makes: Mesa llvmpipe in CI, a real GPU where there is one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "glcontext/context.h"
#include "performer/bvh.h"
#include "performer/character.h"
#include "performer/character_deform.h"
#include "performer/espeak_tts.h"
#include "performer/espeak_visemes.h"
#include "performer/face_deform.h"
#include "performer/local_transforms.h"
#include "performer/procedural_head.h"
#include "performer/render/gpu_deformer.h"
#include "performer/render/renderer.h"
#include "imageio/read.h"
#include "performer/skinning.h"
#include "performer/speech_visemes.h"
#include "performer/viseme_library.h"
#include "performer/weights_expression.h"
#include "performer/weights_track.h"
#include "performer/world_transforms.h"
#include "performer/avatar.h"
#include "performer/gltf_avatar.h"
#include "support/avatar_fixture.h"
#include "support/scratch_dir.h"
#include "support/shared_assets.h"

namespace fs = std::filesystem;

namespace {

using performer::Character;
using performer::CharacterFrame;
using performer::render::GpuDeformer;

glc::Context& context() {
  static const std::unique_ptr<glc::Context> c = [] {
    auto made = glc::Context::create(glc::platform_from_env());
    std::printf("GL renderer: %s\n", made->description().c_str());
    return made;
  }();
  c->make_current();
  return *c;
}

const performer::VisemeLibrary& library() {
  static const performer::VisemeLibrary lib = performer::VisemeLibrary::load_default();
  return lib;
}

// Speech drives the face: espeak-ng's phonemes as visemes, a constant expression and blinks.
const performer::WeightTrack& speech_track() {
  static const performer::WeightTrack track = [] {
    performer::EspeakTts tts;
    const performer::Speech speech = tts.speak("Hello, I am your virtual performer.", "en-us");
    const auto visemes =
        performer::speech_visemes(speech.phonemes, performer::load_default_espeak_visemes("en-us", library()));
    performer::TrackOptions options;
    options.end = speech.duration();
    const auto expressions = performer::constant_expression("smile", 0.6);
    return performer::build_weight_track(visemes, library().visemes(), expressions, options);
  }();
  return track;
}

struct Cmu {
  performer::Bvh bvh;
  Character character;
};

const Cmu& cmu(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Cmu>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<Cmu>();
    slot->bvh = performer::read_bvh(test_support::bvh_asset(name));
    slot->character =
        performer::build_character(slot->bvh.skeleton, performer::build_procedural_head(library().visemes()));
  }
  return *slot;
}

float size_of(const Character& c) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : c.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 d = hi - lo;
  return std::max({d.x, d.y, d.z});
}

struct Agreement {
  float position = 0.0f;  // largest distance, over the character's size
  float normal = 0.0f;    // largest distance between unit normals
};

// One frame both ways: `weights` per target, the joints' world transforms `world` (or the rest pose
// when empty).
Agreement compare_frame(const Character& c, GpuDeformer& gpu, std::span<const float> weights,
                        std::span<const glm::mat4> world) {
  CharacterFrame frame(c);
  std::copy(weights.begin(), weights.end(), frame.weights.begin());
  if (!world.empty()) performer::skinning_matrices(world, c.inverse_bind, frame.matrices);
  performer::deform_character_parallel(frame.job(c));
  gpu.deform(frame.weights, frame.matrices);
  std::vector<glm::vec3> p(c.vertex_count()), n(c.vertex_count());
  gpu.read_back(p, n);
  Agreement a;
  const float size = size_of(c);
  for (std::size_t v = 0; v < c.vertex_count(); ++v) {
    a.position = std::max(a.position, glm::distance(p[v], frame.positions[v]) / size);
    a.normal = std::max(a.normal, glm::distance(n[v], frame.normals[v]));
  }
  return a;
}

// The clip's joints at frame f.
std::vector<glm::mat4> clip_pose(const performer::Bvh& bvh, int f) {
  const performer::Skeleton& sk = bvh.skeleton;
  std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
  performer::local_transforms(sk, performer::frame_values(sk, bvh.motion, f), local);
  performer::world_transforms(sk, local, world);
  return world;
}

// One frame both ways: `weights` per target, the clip's frame `f` (or the rest pose when f < 0).
Agreement compare(const Cmu& m, GpuDeformer& gpu, std::span<const float> weights, int f) {
  return compare_frame(m.character, gpu, weights, f >= 0 ? clip_pose(m.bvh, f) : std::vector<glm::mat4>{});
}

class GpuDeformTest : public ::testing::TestWithParam<const char*> {};

TEST_P(GpuDeformTest, EqualsTheCpuWithSpeechDrivingTheFace) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset(GetParam()));
  if (!performer::EspeakTts::built())
    GTEST_SKIP() << "speech was not built (GPUJ2K_PERFORMER_SPEECH=OFF); espeak-ng drives the face here";
  const Cmu& m = cmu(GetParam());
  for (const auto storage :
       {performer::render::BoneStorage::uniform_block, performer::render::BoneStorage::buffer_texture}) {
    GpuDeformer gpu(context(), m.character, storage);
    const performer::WeightTrack& track = speech_track();
    const performer::ChannelBinding binding =
        performer::bind_channels(track, performer::build_procedural_head(library().visemes()));
    std::vector<float> weights(m.character.targets.size());
    const int frames = m.bvh.motion.frames;
    int compared = 0, with_face = 0;
    Agreement worst;
    for (int k = 0; k < 6; ++k) {
      const int f = k * (frames - 1) / 5;
      const std::size_t t = static_cast<std::size_t>(k) * (track.frame_count() - 1) / 5;
      performer::target_weights(binding, track.frame(t), weights);
      with_face += std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0f; });
      const Agreement a = compare(m, gpu, weights, f);
      EXPECT_LT(a.position, 1e-5f) << "frame " << f;
      EXPECT_LT(a.normal, 1e-4f) << "frame " << f;
      worst.position = std::max(worst.position, a.position);
      worst.normal = std::max(worst.normal, a.normal);
      ++compared;
    }
    EXPECT_EQ(compared, 6);
    EXPECT_GE(with_face, 3);  // the face really was driven
    std::printf("%s, bones in a %s: %d frames, positions within %.2g of the size, normals within %.2g\n", GetParam(),
                gpu.bone_storage().c_str(), compared, worst.position, worst.normal);
  }
}

// Zero face weights give SSD alone, rest bones the face alone: both on the GPU as on the CPU.
TEST_P(GpuDeformTest, FaceAloneAndSkinAlone) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset(GetParam()));
  const Cmu& m = cmu(GetParam());
  GpuDeformer gpu(context(), m.character);
  std::vector<float> none(m.character.targets.size(), 0.0f), some = none;
  some[0] = 0.7f;
  some[some.size() / 2] = 0.4f;
  const Agreement skin_only = compare(m, gpu, none, m.bvh.motion.frames / 3);
  EXPECT_LT(skin_only.position, 1e-5f);
  EXPECT_LT(skin_only.normal, 1e-4f);
  const Agreement face_only = compare(m, gpu, some, -1);
  EXPECT_LT(face_only.position, 1e-5f);
  EXPECT_LT(face_only.normal, 1e-4f);
}

INSTANTIATE_TEST_SUITE_P(Cmu, GpuDeformTest, ::testing::Values("cmu_131_01.bvh", "cmu_131_02.bvh", "cmu_131_03.bvh"),
                         [](const auto& info) { return std::string(info.param).substr(4, 6); });

TEST(GpuDeformer, RefusesWrongCountsAndTooManyActiveTargets) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_01.bvh"));
  const Cmu& m = cmu("cmu_131_01.bvh");
  GpuDeformer gpu(context(), m.character);
  const std::vector<glm::mat4> matrices(m.character.inverse_bind.size(), glm::mat4(1.0f));
  std::vector<float> weights(m.character.targets.size(), 0.0f);
  EXPECT_THROW(gpu.deform(std::span<const float>(weights).first(weights.size() - 1), matrices), std::invalid_argument);
  EXPECT_THROW(gpu.deform(weights, std::span<const glm::mat4>(matrices).first(matrices.size() - 1)),
               std::invalid_argument);
  for (int t = 0; t <= GpuDeformer::kFaceSlots; ++t) weights[static_cast<std::size_t>(t)] = 0.1f;
  EXPECT_THROW(gpu.deform(weights, matrices), std::invalid_argument);
  std::vector<glm::vec3> p(3), n(3);
  EXPECT_THROW(gpu.read_back(p, n), std::invalid_argument);
}

// --- glTF avatars through the same shader path ------------------------------------------------------

// A glTF avatar made by our own code for each clip (support/avatar_fixture.h: the generated performer
// in metres, dressed as a foreign rig), read back as `performer render --gltf` reads it: its skin and
// morph targets as a Character, its joints following the clip's by name.
struct CmuAvatar {
  performer::Bvh bvh;
  performer::FaceModel face;
  Character character;
  performer::AvatarRetarget retarget;

  std::vector<glm::mat4> pose(int f) const {
    std::vector<glm::mat4> joints(character.inverse_bind.size());
    performer::retarget_pose(retarget, clip_pose(bvh, f), joints);
    return joints;
  }
};

const CmuAvatar& cmu_avatar(const std::string& name) {
  static std::map<std::string, std::unique_ptr<CmuAvatar>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<CmuAvatar>();
    slot->bvh = performer::read_bvh(test_support::bvh_asset(name));
    const test_support::ScratchDir dir("gpu_avatar");
    test_support::write_test_avatar(slot->bvh.skeleton, dir / "avatar.glb");
    performer::GltfAvatar avatar = performer::load_gltf_avatar(dir / "avatar.glb", library().visemes());
    slot->character = performer::avatar_character(avatar.skin, avatar.face);
    slot->retarget = performer::retarget_by_name(avatar.skin, slot->bvh.skeleton);
    slot->face = std::move(avatar.face);
  }
  return *slot;
}

class GltfAvatarGpuTest : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfAvatarGpuTest, EqualsTheCpuWithSpeechDrivingTheMorphTargets) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset(GetParam()));
  if (!performer::EspeakTts::built())
    GTEST_SKIP() << "speech was not built (GPUJ2K_PERFORMER_SPEECH=OFF); espeak-ng drives the face here";
  const CmuAvatar& m = cmu_avatar(GetParam());
  ASSERT_FALSE(m.character.targets.empty());
  EXPECT_EQ(m.retarget.unmatched, (std::vector<std::string>{"Prop"}));
  GpuDeformer gpu(context(), m.character);
  const performer::WeightTrack& track = speech_track();
  const performer::ChannelBinding binding = performer::bind_channels(track, m.face);
  std::vector<float> weights(m.character.targets.size());
  const int frames = m.bvh.motion.frames;
  int with_face = 0;
  Agreement worst;
  for (int k = 0; k < 6; ++k) {
    const int f = k * (frames - 1) / 5;
    const std::size_t t = static_cast<std::size_t>(k) * (track.frame_count() - 1) / 5;
    performer::target_weights(binding, track.frame(t), weights);
    with_face += std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0f; });
    const Agreement a = compare_frame(m.character, gpu, weights, m.pose(f));
    EXPECT_LT(a.position, 1e-5f) << "frame " << f;
    EXPECT_LT(a.normal, 1e-5f) << "frame " << f;
    worst.position = std::max(worst.position, a.position);
    worst.normal = std::max(worst.normal, a.normal);
  }
  EXPECT_GE(with_face, 3);  // the morph targets really were driven
  std::printf(
      "%s, glTF avatar (%zu vertices, %zu morph targets, bones in a %s): positions within %.2g of the size, "
      "normals within %.2g\n",
      GetParam(), m.character.vertex_count(), m.character.targets.size(), gpu.bone_storage().c_str(), worst.position,
      worst.normal);
}

INSTANTIATE_TEST_SUITE_P(Cmu, GltfAvatarGpuTest,
                         ::testing::Values("cmu_131_01.bvh", "cmu_131_02.bvh", "cmu_131_03.bvh"),
                         [](const auto& info) { return std::string(info.param).substr(4, 6); });

// --- Rendering (section 3.7) ----------------------------------------------------------------------

// How well a rendered frame shows the character where it is: the pixels that differ from the same
// scene without the character (moved far out of sight) against the CPU-deformed mesh's triangles
// projected with the same camera and filled at pixel centres. Robust to rasteriser differences: only
// the overlap of the two silhouettes (over their union) is measured. Also checks that rendering the
// same frame twice gives the same bytes.
struct Silhouettes {
  double overlap = 0.0;
  std::size_t projected = 0;  // pixels the CPU mesh covers
};

Silhouettes rendered_silhouettes(const Character& c, std::span<const glm::mat4> world, std::span<const float> weights,
                                 int width, int height) {
  GpuDeformer gpu(context(), c);
  performer::render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.effects = performer::render::parse_effects("none");
  performer::render::Renderer renderer(context(), c, settings);

  CharacterFrame frame(c);
  std::copy(weights.begin(), weights.end(), frame.weights.begin());
  performer::skinning_matrices(world, c.inverse_bind, frame.matrices);
  performer::deform_character_parallel(frame.job(c));
  glm::vec3 lo(1e30f), hi(-1e30f), centre(0.0f);
  for (const glm::vec3& p : frame.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  centre = 0.5f * (lo + hi);
  const float aspect = float(width) / float(height);
  const performer::render::Camera camera =
      performer::render::frame_figure(centre, lo.y, hi.y - lo.y, glm::vec3(0, 0, 1), aspect);

  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::uint8_t> with(pixels * 3), without(pixels * 3);
  gpu.deform(frame.weights, frame.matrices);
  renderer.render(gpu, camera, lo.y);
  renderer.read_rgb(with);
  // Deterministic: the same frame again gives the same bytes.
  std::vector<std::uint8_t> again(pixels * 3);
  renderer.render(gpu, camera, lo.y);
  renderer.read_rgb(again);
  EXPECT_EQ(again, with);
  std::vector<glm::mat4> away = frame.matrices;
  for (glm::mat4& a : away) a = glm::translate(glm::mat4(1.0f), camera.eye - 1e4f * (camera.target - camera.eye)) * a;
  gpu.deform(frame.weights, away);
  renderer.render(gpu, camera, lo.y);
  renderer.read_rgb(without);

  // The CPU mesh's silhouette.
  const glm::mat4 vp = camera.projection(aspect) * camera.view();
  std::vector<std::uint8_t> cpu(pixels, 0);
  auto to_pixel = [&](const glm::vec3& p) {
    const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
    return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * width,
                     (0.5f - clip.y / clip.w * 0.5f) * height);  // top row first
  };
  const auto& idx = c.mesh.indices;
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const glm::vec2 a = to_pixel(frame.positions[idx[t]]), b = to_pixel(frame.positions[idx[t + 1]]),
                    d = to_pixel(frame.positions[idx[t + 2]]);
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, d.x})))),
              x1 = std::min(width - 1, int(std::ceil(std::max({a.x, b.x, d.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, d.y})))),
              y1 = std::min(height - 1, int(std::ceil(std::max({a.y, b.y, d.y}))));
    auto edge = [](glm::vec2 p, glm::vec2 q, glm::vec2 r) {
      return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    };
    const float area = edge(a, b, d);
    if (area == 0.0f) continue;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const glm::vec2 q(x + 0.5f, y + 0.5f);
        const float w0 = edge(b, d, q) / area, w1 = edge(d, a, q) / area, w2 = edge(a, b, q) / area;
        if (w0 >= 0 && w1 >= 0 && w2 >= 0) cpu[static_cast<std::size_t>(y * width + x)] = 1;
      }
  }
  std::size_t both = 0, either = 0, shown = 0;
  Silhouettes s;
  for (std::size_t i = 0; i < pixels; ++i) {
    int difference = 0;
    for (std::size_t k = 0; k < 3; ++k)
      difference = std::max(difference, std::abs(int(with[i * 3 + k]) - int(without[i * 3 + k])));
    const bool rendered = difference > 12;
    shown += rendered;
    s.projected += cpu[i];
    both += rendered && cpu[i];
    either += rendered || cpu[i];
  }
  s.overlap = either > 0 ? double(both) / double(either) : 0.0;
  std::printf("silhouette: %zu pixels rendered, %zu projected, overlap %.3f\n", shown, s.projected, s.overlap);
  return s;
}

TEST(Renderer, FrameShowsTheCharacterWhereTheCpuMeshProjects) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_01.bvh"));
  const Cmu& m = cmu("cmu_131_01.bvh");
  constexpr int kW = 200, kH = 150;
  const std::vector<float> neutral(m.character.targets.size(), 0.0f);
  const Silhouettes s = rendered_silhouettes(m.character, clip_pose(m.bvh, 300), neutral, kW, kH);
  EXPECT_GT(s.projected, std::size_t(kW * kH / 50));  // the character is a good part of the frame
  EXPECT_GT(s.overlap, 0.85);
}

TEST(Renderer, FrameShowsTheGltfAvatarWhereTheCpuMeshProjects) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_03.bvh"));
  const CmuAvatar& m = cmu_avatar("cmu_131_03.bvh");
  constexpr int kW = 200, kH = 150;
  std::vector<float> weights(m.character.targets.size(), 0.0f);
  weights[1] = 0.8f;  // a viseme opens the mouth
  const Silhouettes s = rendered_silhouettes(m.character, m.pose(500), weights, kW, kH);
  EXPECT_GT(s.projected, std::size_t(kW * kH / 50));
  EXPECT_GT(s.overlap, 0.85);
}

// The environment sphere is the cube map: looking along each horizontal axis with a 90 degree
// field, each quadrant's mean colour (so orientation and mirroring too) is the face's, within a few
// levels of rounding, filtering and multisampling.
TEST(Renderer, EnvironmentShowsEachCubeFaceTheRightWayRound) {
  const fs::path dir = test_support::shared_dir() / "assets" / "cubemap";
  const fs::path posx = performer::render::cubemap_face_file(dir, "posx");
  REQUIRE_SHARED_FILE(posx.empty() ? dir / "posx.jpg" : posx);
  REQUIRE_SHARED_FILE(test_support::bvh_asset("cmu_131_01.bvh"));
  const Cmu& m = cmu("cmu_131_01.bvh");
  constexpr int kS = 64;
  performer::render::RenderSettings settings;
  settings.width = settings.height = kS;
  settings.effects.environment = true;
  settings.cubemap_dir = dir;
  performer::render::Renderer renderer(context(), m.character, settings);
  struct Face {
    const char* name;
    glm::vec3 direction;
  };
  const Face faces[] = {{"posx", {1, 0, 0}}, {"negx", {-1, 0, 0}}, {"posz", {0, 0, 1}}, {"negz", {0, 0, -1}}};
  std::vector<std::uint8_t> rgb(kS * kS * 3);
  for (const Face& f : faces) {
    SCOPED_TRACE(f.name);
    performer::render::Camera camera;
    camera.eye = glm::vec3(0.0f);
    camera.target = f.direction;
    camera.vertical_fov = 1.5707964f;
    renderer.render_environment(camera);
    renderer.read_rgb(rgb);
    const imageio::Image face = imageio::read_image(performer::render::cubemap_face_file(dir, f.name).string());
    // Means over quadrants (top-left, top-right, bottom-left, bottom-right), RGB, 0..255.
    auto quadrants_of = [](auto&& at, int w, int h) {
      std::array<glm::dvec3, 4> sum{};
      std::array<double, 4> n{};
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const int q = (y >= h / 2 ? 2 : 0) + (x >= w / 2 ? 1 : 0);
          sum[q] += at(x, y);
          n[q] += 1;
        }
      for (int q = 0; q < 4; ++q) sum[q] /= n[q];
      return sum;
    };
    const auto rendered = quadrants_of(
        [&](int x, int y) {
          const std::uint8_t* p = &rgb[(y * kS + x) * 3];
          return glm::dvec3(p[0], p[1], p[2]);
        },
        kS, kS);
    const double scale = 255.0 / ((1 << face.bits_per_sample) - 1);
    const auto expected = quadrants_of(
        [&](int x, int y) { return glm::dvec3(face.at(x, y, 0), face.at(x, y, 1), face.at(x, y, 2)) * scale; },
        face.width, face.height);
    // These files keep each face bottom row first (the sky at the bottom of the side faces), and a
    // viewer inside an OpenGL cube map sees a face's s axis run right to left (the cube map
    // convention is left-handed): the view is the file turned by 180 degrees, quadrant q showing
    // the file's quadrant 3 - q, with the sky above the horizon.
    for (int q = 0; q < 4; ++q)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(rendered[q][k], expected[3 - q][k], 6.0) << "quadrant " << q << " channel " << k;
    EXPECT_GT(rendered[0].z + rendered[1].z, rendered[2].z + rendered[3].z) << "the sky (blue) above";
  }
}

}  // namespace
