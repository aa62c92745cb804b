// `performer pose`: the whole performer (body grown around the BVH's skeleton, procedural head on its
// head joint) posed by a range of motion capture frames, the face optionally driven by a weight track,
// every frame deformed by equation 3.20 (face first, then skinning) and written as a mesh.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "performer/weights_track.h"

namespace performer::cli {

struct PoseCommand {
  std::filesystem::path bvh;
  int first_frame = 0;  // inclusive BVH frame indices, from 0
  int last_frame = 0;
  std::filesystem::path out_dir;  // frame_NNNNN.ply, NNNNN the BVH frame index (created if missing)
  std::string format = "ply";     // ply or obj
  unsigned threads = 0;           // 0: all hardware threads
  // Optional face weights, sampled at each frame's time measured from first_frame (linearly between
  // the track's frames, clamped to its first and last). nullptr: the neutral face throughout.
  const WeightTrack* weights = nullptr;
};

// Throws std::invalid_argument for a bad format or a frame range outside the file, BvhError for an
// unreadable file, std::runtime_error for files that cannot be written; each message is one line.
// Progress and a summary go to `log`.
void run_pose(const PoseCommand& command, std::FILE* log);

}  // namespace performer::cli
