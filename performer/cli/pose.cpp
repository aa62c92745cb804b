#include "pose.h"

#include <algorithm>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

#include "performer/bvh.h"
#include "performer/character.h"
#include "performer/character_deform.h"
#include "performer/face_deform.h"
#include "performer/local_transforms.h"
#include "performer/mesh_io.h"
#include "performer/procedural_head.h"
#include "performer/skinning.h"
#include "performer/viseme_library.h"
#include "performer/viseme_set.h"
#include "performer/world_transforms.h"
#include "cli_character.h"
#include "track_sampling.h"

namespace performer::cli {

namespace {

std::filesystem::path frame_path(const std::filesystem::path& dir, int frame, const std::string& format) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.%s", frame, format.c_str());
  return dir / name;
}

}  // namespace

void run_pose(const PoseCommand& command, std::FILE* log) {
  if (command.format != "ply" && command.format != "obj")
    throw std::invalid_argument("--format must be ply or obj, not \"" + command.format + "\"");
  const Bvh bvh = read_bvh(command.bvh);
  const Skeleton& skeleton = bvh.skeleton;
  check_frame_range(bvh, command.bvh, command.first_frame, command.last_frame);
  const CliCharacter built = build_cli_character(skeleton, command.threads);
  const FaceModel& face = built.face;
  const Character& character = built.character;
  std::fprintf(log, "pose: character of %zu vertices (%zu head), %zu triangles, %zu face targets\n",
               character.vertex_count(), character.head_count, character.mesh.indices.size() / 3,
               character.targets.size());

  // The track's channels bound to the head's targets, which the character keeps in the face's order.
  ChannelBinding binding;
  std::vector<float> channel_values;
  if (command.weights) {
    binding = bind_channels(*command.weights, face);
    channel_values.resize(command.weights->channel_count());
    if (!binding.unmatched.empty()) {
      std::string names;
      for (const std::string& n : binding.unmatched) names += (names.empty() ? "" : ", ") + n;
      std::fprintf(log, "pose: no target for channel%s %s (ignored)\n", binding.unmatched.size() > 1 ? "s" : "",
                   names.c_str());
    }
  }

  std::filesystem::create_directories(command.out_dir);
  // Sized once; every frame below only fills them.
  CharacterFrame frame(character);
  const CharacterDeformJob job = frame.job(character);
  std::vector<glm::mat4> local(skeleton.joints.size()), world(skeleton.joints.size());
  for (int f = command.first_frame; f <= command.last_frame; ++f) {
    local_transforms(skeleton, frame_values(skeleton, bvh.motion, f), local);
    world_transforms(skeleton, local, world);
    skinning_matrices(world, character.inverse_bind, frame.matrices);
    if (command.weights) {
      sample_track(*command.weights, (f - command.first_frame) * bvh.motion.frame_time, channel_values);
      target_weights(binding, channel_values, frame.weights);
    }
    deform_character_parallel(job, command.threads);
    const MeshView mesh{frame.positions, frame.normals, character.mesh.indices};
    const auto file = frame_path(command.out_dir, f, command.format);
    if (command.format == "ply")
      write_ply(file, mesh);
    else
      write_obj(file, mesh);
  }
  std::fprintf(log, "pose: frames %d..%d written to %s\n", command.first_frame, command.last_frame,
               command.out_dir.string().c_str());
}

}  // namespace performer::cli
