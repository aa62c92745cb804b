// `performer face`: a weight track (from `performer visemes`) drives a face, and every frame's
// deformed mesh (equations 3.9 and 3.11) is written for inspection. The face is the procedural head,
// or a glTF avatar whose morph targets carry Oculus or ARKit names.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "performer/face_model.h"
#include "performer/viseme_set.h"
#include "performer/weights_track.h"

namespace performer::cli {

struct FaceCommand {
  std::filesystem::path out_dir;  // frame_00000.ply, ... (created if missing)
  std::string format = "ply";     // ply or obj
  std::filesystem::path gltf;     // empty: the procedural head
  unsigned threads = 0;           // 0: all hardware threads
};

// The procedural head, or the avatar's face (load_gltf_face), named on `log` in one line.
FaceModel load_face(const std::filesystem::path& gltf, const VisemeSet& set, std::FILE* log);

// Throws std::invalid_argument for a bad format, std::runtime_error for files that cannot be written.
// Channels of the track the face has no target for are named on `log` in one line.
void run_face(const FaceCommand& command, const WeightTrack& track, const FaceModel& face, std::FILE* log);

// "frame_00042.ply": frames are numbered from 0, five digits, so they sort.
std::filesystem::path frame_file(const std::filesystem::path& dir, std::size_t frame, const std::string& format);

}  // namespace performer::cli
