#include "face.h"

#include <cstdio>
#include <stdexcept>
#include <vector>

#include "performer/face_deform.h"
#include "performer/gltf_face.h"
#include "performer/mesh_io.h"
#include "performer/procedural_head.h"

namespace performer::cli {

FaceModel load_face(const std::filesystem::path& gltf, const VisemeSet& set, std::FILE* log) {
  if (gltf.empty()) {
    FaceModel head = build_procedural_head(set);
    std::fprintf(log, "face: procedural head, %zu vertices, %zu targets\n", head.vertex_count(), head.targets.size());
    return head;
  }
  GltfFace avatar = load_gltf_face(gltf, set);
  std::fprintf(log, "face: %s mesh \"%s\", %zu vertices, %zu targets%s\n", gltf.string().c_str(), avatar.mesh.c_str(),
               avatar.model.vertex_count(), avatar.model.targets.size(),
               avatar.missing.empty() ? "" : (", " + std::to_string(avatar.missing.size()) + " missing").c_str());
  return std::move(avatar.model);
}

std::filesystem::path frame_file(const std::filesystem::path& dir, std::size_t frame, const std::string& format) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05zu.%s", frame, format.c_str());
  return dir / name;
}

void run_face(const FaceCommand& command, const WeightTrack& track, const FaceModel& face, std::FILE* log) {
  if (command.format != "ply" && command.format != "obj")
    throw std::invalid_argument("--format must be ply or obj, not \"" + command.format + "\"");
  std::filesystem::create_directories(command.out_dir);
  const ChannelBinding binding = bind_channels(track, face);
  if (!binding.unmatched.empty()) {
    std::string names;
    for (const std::string& n : binding.unmatched) names += (names.empty() ? "" : ", ") + n;
    std::fprintf(log, "face: no target for channel%s %s (ignored)\n", binding.unmatched.size() > 1 ? "s" : "",
                 names.c_str());
  }
  const FaceStreams streams(face);
  std::vector<float> weights(binding.target_count);
  std::vector<glm::vec3> positions(face.vertex_count()), normals(face.vertex_count());
  for (std::size_t f = 0; f < track.frame_count(); ++f) {
    target_weights(binding, track.frame(f), weights);
    const FaceDeformJob job{face.positions, face.normals, streams.positions, streams.normals, weights,
                            positions,      normals};
    deform_face_parallel(job, command.threads);
    const MeshView mesh{positions, normals, face.indices};
    const auto file = frame_file(command.out_dir, f, command.format);
    if (command.format == "ply")
      write_ply(file, mesh);
    else
      write_obj(file, mesh);
  }
  std::fprintf(log, "face: %zu frames at %g fps written to %s\n", track.frame_count(), track.fps,
               command.out_dir.string().c_str());
}

}  // namespace performer::cli
