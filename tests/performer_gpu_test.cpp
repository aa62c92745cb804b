// Equation 3.20 on the GPU (performer/render/gpu_deformer.h) against the CPU jobs it mirrors
// (character_deform.h): on the three CMU clips at several frames with speech driving the face, the
// deformed positions and normals agree within 1e-5 of the character's size. Runs on whatever context
// the GL layer makes: Mesa llvmpipe in CI, a real GPU where there is one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

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
#include "performer/skinning.h"
#include "performer/speech_visemes.h"
#include "performer/viseme_library.h"
#include "performer/weights_expression.h"
#include "performer/weights_track.h"
#include "performer/world_transforms.h"
#include "support/shared_assets.h"

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
    slot->character = performer::build_character(slot->bvh.skeleton, performer::build_procedural_head(library().visemes()));
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

// One frame both ways: `weights` per target, the clip's frame `f` (or the rest pose when f < 0).
Agreement compare(const Cmu& m, GpuDeformer& gpu, std::span<const float> weights, int f) {
  const Character& c = m.character;
  const performer::Skeleton& sk = m.bvh.skeleton;
  CharacterFrame frame(c);
  std::copy(weights.begin(), weights.end(), frame.weights.begin());
  if (f >= 0) {
    std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size());
    performer::local_transforms(sk, performer::frame_values(sk, m.bvh.motion, f), local);
    performer::world_transforms(sk, local, world);
    performer::skinning_matrices(world, c.inverse_bind, frame.matrices);
  }
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

class GpuDeformTest : public ::testing::TestWithParam<const char*> {};

TEST_P(GpuDeformTest, EqualsTheCpuWithSpeechDrivingTheFace) {
  REQUIRE_SHARED_FILE(test_support::bvh_asset(GetParam()));
  const Cmu& m = cmu(GetParam());
  for (const auto storage : {performer::render::BoneStorage::uniform_block, performer::render::BoneStorage::buffer_texture}) {
  GpuDeformer gpu(context(), m.character, storage);
  const performer::WeightTrack& track = speech_track();
  const performer::ChannelBinding binding = performer::bind_channels(track, performer::build_procedural_head(library().visemes()));
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

}  // namespace
