// performer_bench: vertices per second of equation 3.20 (face deformation of the head range, then
// SSD of every vertex; thesis 3.6) on the CPU and in the GPU's vertex shader, and Table 3.9: frames
// per second of the rendered character with each effect of section 3.7, GPU or CPU deformation.
//
//   performer_bench [BVH]   (default: ../shared/assets/bvh/cmu_131_01.bvh from GPUJ2K_SOURCE_DIR)
//
// Two sizes: (a) the thesis' character, about 15,000 vertices (table 3.8: head 4,098 + body 6,442 +
// legs 4,850 = 15,390), from a coarser body grid and head; (b) about one million vertices, made by
// replicating the (a) character's streams (every body copy, then every head copy, so the head is
// still one contiguous range with its DVs replicated alongside): the same per-vertex work as the
// real character, only more of it. Each is timed single-threaded and on all hardware threads:
// warm-up, then repetitions, median reported.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <utility>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "glcontext/context.h"
#include "performer/bvh.h"
#include "performer/render/gpu_deformer.h"
#include "performer/render/renderer.h"
#include "performer/character.h"
#include "performer/character_deform.h"
#include "performer/local_transforms.h"
#include "performer/procedural_head.h"
#include "performer/skinning.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"
#include "performer/world_transforms.h"

#ifndef GPUJ2K_SOURCE_DIR_DEFAULT
#define GPUJ2K_SOURCE_DIR_DEFAULT "."
#endif

namespace {

using performer::Character;

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "unknown CPU";
}

// `copies` characters' worth of streams: all bodies, then all heads (see the top of this file).
Character replicate(const Character& c, std::size_t copies) {
  Character r;
  const std::size_t body = c.head_first, head = c.head_count, n = c.vertex_count();
  const auto slots = static_cast<std::size_t>(c.influences);
  r.influences = c.influences;
  r.inverse_bind = c.inverse_bind;
  r.head_joint = c.head_joint;
  r.head_placement = c.head_placement;
  r.head_first = body * copies;
  r.head_count = head * copies;
  auto append = [&](std::size_t first, std::size_t count) {
    for (std::size_t k = 0; k < copies; ++k) {
      r.mesh.positions.insert(r.mesh.positions.end(), c.mesh.positions.begin() + first,
                              c.mesh.positions.begin() + first + count);
      r.mesh.normals.insert(r.mesh.normals.end(), c.mesh.normals.begin() + first,
                            c.mesh.normals.begin() + first + count);
      r.joint_indices.insert(r.joint_indices.end(), c.joint_indices.begin() + first * slots,
                             c.joint_indices.begin() + (first + count) * slots);
      r.joint_weights.insert(r.joint_weights.end(), c.joint_weights.begin() + first * slots,
                             c.joint_weights.begin() + (first + count) * slots);
    }
  };
  append(0, body);
  append(body, n - body);
  for (const performer::MorphTarget& t : c.targets) {
    performer::MorphTarget rt;
    rt.name = t.name;
    for (std::size_t k = 0; k < copies; ++k) {
      rt.position_deltas.insert(rt.position_deltas.end(), t.position_deltas.begin(), t.position_deltas.end());
      rt.normal_deltas.insert(rt.normal_deltas.end(), t.normal_deltas.begin(), t.normal_deltas.end());
    }
    r.targets.push_back(std::move(rt));
  }
  // Indices are not needed to deform; the mesh is never drawn here.
  return r;
}

// The thesis' shader blends 2 viseme DVs, 2 expression DVs and the eye channel (3.4.5): five
// targets on per frame, as mid-coarticulation speech with a smile and a blink would have.
int set_weights(const Character& c, std::vector<float>& weights) {
  std::fill(weights.begin(), weights.end(), 0.0f);
  const char* names[] = {"AA", "O", "smile", "surprise", "blink"};
  const float values[] = {0.6f, 0.4f, 0.7f, 0.2f, 0.5f};
  int active = 0;
  for (int i = 0; i < 5; ++i)
    for (std::size_t t = 0; t < c.targets.size(); ++t)
      if (c.targets[t].name == names[i]) {
        weights[t] = values[i];
        ++active;
      }
  // Viseme names differ between sets; make up the two viseme slots from the first viseme targets.
  for (std::size_t t = 1; t < c.targets.size() && active < 5; ++t)
    if (weights[t] == 0.0f) {
      weights[t] = 0.5f;
      ++active;
    }
  return active;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void run(const char* label, const Character& c, const std::vector<glm::mat4>& matrices, unsigned threads,
         int repetitions) {
  performer::CharacterFrame frame(c);
  frame.matrices = matrices;
  const int active = set_weights(c, frame.weights);
  const performer::CharacterDeformJob job = frame.job(c);
  auto once = [&] {
    if (threads == 1)
      performer::deform_character(job);
    else
      performer::deform_character_parallel(job, threads);
  };
  for (int i = 0; i < 3; ++i) once();  // warm-up: caches, page faults, thread start-up paths
  std::vector<double> seconds;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    once();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  const double s = median(seconds);
  std::printf(
      "%-10s %9zu vertices (%zu head), %d influences, %d/%zu face targets active, %2u thread%s: "
      "%8.3f ms/frame  %7.1f Mvertices/s  (median of %d)\n",
      label, c.vertex_count(), c.head_count, c.influences, active, c.targets.size(), threads, threads == 1 ? " " : "s",
      s * 1e3, c.vertex_count() / s * 1e-6, repetitions);
}

// Table 3.9: frames per second of the character drawn with each effect, deformed on the GPU
// (equation 3.20 in the vertex shader) or on the CPU and uploaded, into the same renderer. A frame
// is timed to glFinish (drawn, not read back).
void table_3_9(glc::Context& context, const Character& c, const std::vector<glm::mat4>& matrices,
               const std::filesystem::path& cubemap, unsigned threads) {
  performer::render::GpuDeformer gpu(context, c);
  performer::CharacterFrame frame(c);
  frame.matrices = matrices;
  set_weights(c, frame.weights);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : c.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  performer::deform_character_parallel(frame.job(c), threads);
  glm::vec3 centre(0.0f);
  for (const glm::vec3& p : frame.positions) centre += p;
  centre /= static_cast<float>(c.vertex_count());
  const char* effect_sets[] = {"none", "env", "hair", "snow", "toon", "env,hair,snow"};
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{1280, 720}})
    for (const char* effects : effect_sets) {
      performer::render::RenderSettings settings;
      settings.width = w;
      settings.height = h;
      settings.effects = performer::render::parse_effects(effects);
      settings.cubemap_dir = cubemap;
      if (settings.effects.environment && performer::render::cubemap_face_file(cubemap, "posx").empty()) continue;
      performer::render::Renderer renderer(context, c, settings);
      const performer::render::Camera camera = performer::render::frame_figure(
          centre, lo.y + (centre.y - (lo.y + hi.y) / 2), hi.y - lo.y, glm::vec3(0, 0, 1), float(w) / float(h));
      performer::render::Snow snow(1500, centre, 1.6f * (hi.y - lo.y), lo.y, 1.4f * (hi.y - lo.y));
      for (const bool on_gpu : {true, false}) {
        auto once = [&] {
          if (on_gpu) {
            gpu.deform(frame.weights, frame.matrices);
          } else {
            performer::deform_character_parallel(frame.job(c), threads);
            gpu.upload(frame.positions, frame.normals);
          }
          snow.step(1.0f / 30.0f);
          renderer.render(gpu, camera, lo.y, &snow);
          context.gl().glFinish();
        };
        for (int i = 0; i < 3; ++i) once();
        std::vector<double> seconds;
        for (int i = 0; i < 15; ++i) {
          const auto start = std::chrono::steady_clock::now();
          once();
          seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        const double s = median(seconds);
        std::printf("%4dx%-4d %-14s %s deformation: %7.2f ms/frame %7.1f fps\n", w, h, effects, on_gpu ? "GPU" : "CPU",
                    s * 1e3, 1.0 / s);
      }
    }
}

// The million-vertex row: equation 3.20 alone on the GPU (transform feedback, no drawing), to
// glFinish.
void million_on_gpu(glc::Context& context, const Character& c, const std::vector<glm::mat4>& matrices) {
  performer::render::GpuDeformer gpu(context, c);
  std::vector<float> weights(c.targets.size());
  set_weights(c, weights);
  for (int i = 0; i < 3; ++i) gpu.deform(weights, matrices), context.gl().glFinish();
  std::vector<double> seconds;
  for (int i = 0; i < 15; ++i) {
    const auto start = std::chrono::steady_clock::now();
    gpu.deform(weights, matrices);
    context.gl().glFinish();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  const double s = median(seconds);
  std::printf("(b) on the GPU: %zu vertices, %8.3f ms/frame  %7.1f Mvertices/s  %6.1f fps\n", c.vertex_count(), s * 1e3,
              c.vertex_count() / s * 1e-6, 1.0 / s);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const char* root = std::getenv("GPUJ2K_SOURCE_DIR");
    const std::filesystem::path bvh_path = argc > 1 ? std::filesystem::path(argv[1])
                                                    : std::filesystem::path(root ? root : GPUJ2K_SOURCE_DIR_DEFAULT) /
                                                          ".." / "shared" / "assets" / "bvh" / "cmu_131_01.bvh";
    const performer::Bvh bvh = performer::read_bvh(bvh_path);
    const performer::Skeleton& sk = bvh.skeleton;

    // (a) Table 3.8's proportions: head about 4,100 vertices, body about 11,300.
    performer::HeadParams head_params;
    head_params.rings = 49;
    head_params.segments = 76;
    const performer::FaceModel face = performer::build_procedural_head(
        performer::load_viseme_set(performer::default_viseme_dir() / "visemes.tsv"), head_params);
    performer::CharacterParams params;
    params.body.grid_cells = 113;
    const Character thesis = performer::build_character(sk, face, params);

    // A posed frame from the middle of the capture.
    std::vector<glm::mat4> local(sk.joints.size()), world(sk.joints.size()), matrices(sk.joints.size());
    performer::local_transforms(sk, performer::frame_values(sk, bvh.motion, bvh.motion.frames / 2), local);
    performer::world_transforms(sk, local, world);
    performer::skinning_matrices(world, thesis.inverse_bind, matrices);

    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    std::printf("performer_bench: equation 3.20 on the CPU (face DVs on the head range, then SSD)\n");
    std::printf("machine: %s, %u hardware threads\n", cpu_model().c_str(), hw);
    std::printf("motion: %s, frame %d\n", bvh_path.filename().string().c_str(), bvh.motion.frames / 2);
    std::printf("(a) thesis-sized character: body grid %d cells, head %dx%d; table 3.8 has 15390 vertices\n",
                params.body.grid_cells, head_params.rings, head_params.segments);
    run("(a)", thesis, matrices, 1, 201);
    run("(a)", thesis, matrices, hw, 201);

    const std::size_t copies = (1000000 + thesis.vertex_count() - 1) / thesis.vertex_count();
    const Character million = replicate(thesis, copies);
    std::printf("(b) one million: the (a) streams replicated %zu times\n", copies);
    run("(b)", million, matrices, 1, 15);
    run("(b)", million, matrices, hw, 15);

    // The GPU path, on whatever renderer the GL layer finds (named on the first line).
    const auto context = glc::Context::create(glc::platform_from_env());
    std::printf("GPU: %s\n", context->description().c_str());
    million_on_gpu(*context, million, matrices);
    std::printf("Table 3.9: frames per second, (a) character, every effect, GPU or CPU (%u threads) deformation\n", hw);
    table_3_9(*context, thesis, matrices,
              std::filesystem::path(root ? root : GPUJ2K_SOURCE_DIR_DEFAULT) / ".." / "shared" / "assets" / "cubemap",
              hw);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "performer_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
