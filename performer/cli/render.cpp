#include "render.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "glcontext/context.h"
#include "imageio/image.h"
#include "imageio/write.h"
#include "performer/avatar.h"
#include "performer/body_mesh.h"
#include "performer/bvh.h"
#include "performer/character.h"
#include "performer/face_deform.h"
#include "performer/gltf_avatar.h"
#include "performer/local_transforms.h"
#include "performer/procedural_head.h"
#include "performer/render/gpu_deformer.h"
#include "performer/render/renderer.h"
#include "performer/render/scene.h"
#include "performer/skinning.h"
#include "performer/video/video_writer.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"
#include "performer/world_transforms.h"
#include "cli_character.h"
#include "track_sampling.h"

namespace performer::cli {

namespace {

// The frame sink: an MP4 (appearing only when finished) or a folder of PNGs (written into a
// temporary folder that is renamed into place at the end).
class FrameSink {
 public:
  FrameSink(const RenderCommand& c, const Speech* speech) : out_(c.out) {
    if (c.out.extension() == ".mp4") {
      video::VideoSettings vs;
      vs.width = c.width;
      vs.height = c.height;
      vs.fps = c.fps;
      video::AudioTrack audio;
      if (speech && speech->sample_rate > 0 && !speech->samples.empty()) {
        audio.sample_rate = speech->sample_rate;
        audio.samples = speech->samples;
      }
      video_ = std::make_unique<video::VideoWriter>(c.out, vs, audio.samples.empty() ? nullptr : &audio);
      return;
    }
    if (c.out.has_extension())
      throw std::invalid_argument("-o must be an .mp4 file or a folder for PNG frames, not \"" + c.out.string() + "\"");
    if (std::filesystem::exists(c.out) && !std::filesystem::is_empty(c.out))
      throw std::invalid_argument(c.out.string() + " exists and is not empty");
    folder_ = c.out;
    folder_ += ".partial";
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  ~FrameSink() {
    if (!done_ && !folder_.empty()) {
      std::error_code ignored;
      std::filesystem::remove_all(folder_, ignored);
    }
  }
  void add(std::span<const std::uint8_t> rgb, int width, int height) {
    if (video_) {
      video_->write_frame(rgb);
    } else {
      imageio::Image image;
      image.width = width;
      image.height = height;
      image.channels = 3;
      image.bits_per_sample = 8;
      image.pixels.assign(rgb.begin(), rgb.end());
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.png", count_);
      imageio::write_image((folder_ / name).string(), image);
    }
    ++count_;
  }
  void finish() {
    if (video_) {
      video_->finish();
    } else {
      std::filesystem::remove(out_);  // an empty folder given as the target
      std::filesystem::rename(folder_, out_);
    }
    done_ = true;
  }

 private:
  std::filesystem::path out_, folder_;
  std::unique_ptr<video::VideoWriter> video_;
  int count_ = 0;
  bool done_ = false;
};

// What is rendered: the generated performer, whose skeleton is the clip's, or a glTF avatar.
struct Figure {
  FaceModel face;  // its targets are the character's, in order: what a weight track binds to
  Character character;
  std::optional<AvatarRetarget> retarget;  // a skinned avatar's joints, following the clip's
  std::vector<glm::vec3> rest_joints;      // the posed joints' rest positions, in the character's units
  int root = 0;                            // the joint the camera follows
};

Figure generated_figure(const Skeleton& skeleton, unsigned threads, FaceModel face) {
  CliCharacter built = build_cli_character(skeleton, threads, std::move(face));
  return {std::move(built.face), std::move(built.character), std::nullopt, rest_joint_positions(skeleton), 0};
}

std::string joined(const std::vector<std::string>& names, std::size_t limit) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < limit; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > limit) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

Figure avatar_figure(const std::filesystem::path& file, const Skeleton& skeleton, unsigned threads, std::FILE* log) {
  GltfAvatar avatar = load_gltf_avatar(file, load_viseme_set(default_viseme_dir() / "visemes.tsv"));
  if (!avatar.skinned) {
    std::fprintf(log, "render: %s has no skin; its face (mesh \"%s\", %zu targets) goes on the generated body\n",
                 file.string().c_str(), avatar.mesh.c_str(), avatar.face.targets.size());
    return generated_figure(skeleton, threads, std::move(avatar.face));
  }
  Figure figure;
  figure.retarget = retarget_by_name(avatar.skin, skeleton);
  const AvatarRetarget& r = *figure.retarget;
  if (r.root < 0) {
    std::vector<std::string> names;
    for (const SkinJoint& j : avatar.skin.joints) names.push_back(j.name);
    throw std::invalid_argument(file.string() + ": none of the avatar's joints (" + joined(names, 8) +
                                ") is named like a joint of the motion capture");
  }
  figure.character = avatar_character(avatar.skin, avatar.face);
  figure.face = std::move(avatar.face);
  for (const glm::mat4& m : r.rest_world) figure.rest_joints.emplace_back(m[3]);
  figure.root = r.root;
  const std::size_t joints = avatar.skin.joints.size();
  std::fprintf(log,
               "render: avatar %s, mesh \"%s\", %zu face targets; %zu of %zu joints follow the clip by name, "
               "at %.4g avatar units per clip unit%s%s\n",
               file.string().c_str(), avatar.mesh.c_str(), figure.face.targets.size(), joints - r.unmatched.size(),
               joints, r.scale,
               r.unmatched.empty() ? "" : "; in bind pose on their parents: ", joined(r.unmatched, 12).c_str());
  if (figure.face.targets.empty())
    std::fprintf(log, "render: the avatar has none of the morph targets the performer needs; its face does not move\n");
  return figure;
}

// The figure's joints for frame f of the clip: the clip's own, or the avatar's following them.
void pose_figure(const Figure& figure, const Bvh& bvh, int f, std::span<glm::mat4> local,
                 std::span<glm::mat4> skeleton_world, std::span<glm::mat4> out) {
  local_transforms(bvh.skeleton, frame_values(bvh.skeleton, bvh.motion, f), local);
  if (!figure.retarget) {
    world_transforms(bvh.skeleton, local, out);
    return;
  }
  world_transforms(bvh.skeleton, local, skeleton_world);
  retarget_pose(*figure.retarget, skeleton_world, out);
}

void progress(std::FILE* log, bool terminal, int done, int total, double seconds) {
  if (!terminal) return;
  const int width = 30, filled = total > 0 ? done * width / total : width;
  std::fprintf(log, "\rrender [%.*s%*s] %d/%d frames, %.1f fps", filled, "##############################",
               width - filled, "", done, total, seconds > 0 ? done / seconds : 0.0);
  if (done == total) std::fputc('\n', log);
  std::fflush(log);
}

}  // namespace

void run_render(const RenderCommand& c, std::FILE* log) {
  const render::Effects effects = render::parse_effects(c.effects);
  if (c.fps < 1 || c.fps > 240) throw std::invalid_argument("--fps must be 1 to 240");
  const Bvh bvh = read_bvh(c.bvh);
  const Skeleton& skeleton = bvh.skeleton;
  const int last = c.last_frame < 0 ? bvh.motion.frames - 1 : c.last_frame;
  check_frame_range(bvh, c.bvh, c.first_frame, last);
  if (effects.environment && !std::filesystem::is_directory(c.cubemap_dir))
    throw std::invalid_argument("the env effect needs a cube map folder (--cubemap), \"" + c.cubemap_dir.string() +
                                "\" is not one");
  // The output first: a bad path fails before the expensive part, and before any log line.
  FrameSink sink(c, c.speech);
  // Output frames at c.fps over the chosen span of the clip (its frames at their own rate).
  const double duration = (last - c.first_frame) * bvh.motion.frame_time;
  const int out_frames = std::max(1, static_cast<int>(std::floor(duration * c.fps + 1e-9)) + 1);

  const Figure figure =
      c.gltf.empty() ? generated_figure(skeleton, c.threads,
                                        build_procedural_head(load_viseme_set(default_viseme_dir() / "visemes.tsv")))
                     : avatar_figure(c.gltf, skeleton, c.threads, log);
  const FaceModel& face = figure.face;
  const Character& character = figure.character;

  const auto context =
      glc::Context::create(c.gl_platform.empty() ? glc::platform_from_env() : glc::parse_platform(c.gl_platform));
  render::GpuDeformer deformer(*context, character);
  render::RenderSettings rs;
  rs.width = c.width;
  rs.height = c.height;
  rs.effects = effects;
  rs.cubemap_dir = c.cubemap_dir;
  render::Renderer renderer(*context, character, rs);
  std::fprintf(log, "render: %zu vertices, %d frames at %d fps, %dx%d, effects %s, on %s\n", character.vertex_count(),
               out_frames, c.fps, c.width, c.height, render::effects_name(effects).c_str(),
               context->description().c_str());

  // The figure's height from the rest pose; the floor where the motion puts its lowest joint, less
  // what the skin reaches below the lowest joint at rest (the soles).
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : character.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float height = hi.y - lo.y;
  const std::size_t joints = character.inverse_bind.size();
  std::vector<glm::mat4> local(skeleton.joints.size()), skeleton_world(skeleton.joints.size()), world(joints),
      matrices(joints);
  float floor_y = 1e30f;
  {
    float rest_lowest = 1e30f;
    for (const glm::vec3& j : figure.rest_joints) rest_lowest = std::min(rest_lowest, j.y);
    const float sole = rest_lowest - lo.y;
    for (int f = c.first_frame; f <= last; f += std::max(1, (last - c.first_frame) / 200)) {
      pose_figure(figure, bvh, f, local, skeleton_world, world);
      for (const glm::mat4& m : world) floor_y = std::min(floor_y, m[3][1] - sole);
    }
  }
  std::unique_ptr<render::Snow> snow;
  if (effects.snow) snow = std::make_unique<render::Snow>(1500, glm::vec3(0.0f), 1.6f * height, floor_y, 1.4f * height);

  ChannelBinding binding;
  std::vector<float> channel_values;
  if (c.weights) {
    binding = bind_channels(*c.weights, face);
    channel_values.resize(c.weights->channel_count());
  }
  std::vector<float> face_weights(character.targets.size(), 0.0f);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(c.width) * static_cast<std::size_t>(c.height) * 3);
  const bool terminal = ::isatty(::fileno(log)) != 0;
  const auto start = std::chrono::steady_clock::now();
  glm::vec3 tracked(0.0f), facing(0.0f, 0.0f, 1.0f);
  const float aspect = static_cast<float>(c.width) / static_cast<float>(c.height);
  for (int k = 0; k < out_frames; ++k) {
    const double t = static_cast<double>(k) / c.fps;
    const int f = std::min(last, c.first_frame + static_cast<int>(std::lround(t / bvh.motion.frame_time)));
    pose_figure(figure, bvh, f, local, skeleton_world, world);
    skinning_matrices(world, character.inverse_bind, matrices);
    if (c.weights) {
      sample_track(*c.weights, t, channel_values);
      target_weights(binding, channel_values, face_weights);
      keep_strongest(face_weights, render::GpuDeformer::kFaceSlots);
    }
    deformer.deform(face_weights, matrices);
    // The camera follows the hips smoothly, from the side the figure faced at the start: the root's
    // +Z (the way figures face at rest) turned as its skinning matrix turns it from the rest pose.
    const auto root = static_cast<std::size_t>(figure.root);
    const glm::vec3 hips(world[root][3]);
    tracked = k == 0 ? hips : tracked + 0.15f * (hips - tracked);
    if (k == 0) facing = glm::vec3(matrices[root] * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
    const render::Camera camera = render::frame_figure(tracked, floor_y, height, facing, aspect);
    if (snow) {
      snow->recentre(glm::vec3(tracked.x, 0.0f, tracked.z));
      snow->step(1.0f / static_cast<float>(c.fps));
    }
    renderer.render(deformer, camera, floor_y, snow.get());
    renderer.read_rgb(rgb);
    sink.add(rgb, c.width, c.height);
    progress(log, terminal, k + 1, out_frames,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  sink.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(log, "render: %d frames written to %s in %.1f s (%.1f fps)\n", out_frames, c.out.string().c_str(),
               seconds, out_frames / seconds);
}

}  // namespace performer::cli
