// `performer render`: the performer as a viewer sees it. Motion capture and speech in; every
// output frame the character deformed on the GPU (equation 3.20 in a vertex shader), rendered with
// section 3.7's effects, and written to an MP4 with the speech (or to PNG frames).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "performer/speech.h"
#include "performer/weights_track.h"

namespace performer::cli {

struct RenderCommand {
  std::filesystem::path bvh;
  int first_frame = 0;  // BVH frames, inclusive; last_frame < 0: to the end
  int last_frame = -1;
  std::filesystem::path out;  // .mp4, or a folder for frame_00000.png, ...
  std::string effects = "none";
  int width = 640, height = 480;
  int fps = 30;
  std::string gl_platform;  // empty: GPUJ2K_GL or auto
  std::filesystem::path cubemap_dir;
  unsigned threads = 0;
  // A glTF avatar (.glb or .gltf) instead of the generated performer. Skinned: its mesh is the
  // character, its joints follow the clip's joints of the same name (avatar.h; the others keep their
  // bind pose relative to their parents) and its morph targets are the face. Not skinned but with
  // morph targets: that face goes on the generated body's head joint, in place of the procedural head.
  std::filesystem::path gltf;
  // Face weights over time (from speech, keyframes or a CSV); nullptr: a neutral face. `speech`: the
  // audio to put in the video when the weights came from text.
  const WeightTrack* weights = nullptr;
  const Speech* speech = nullptr;
};

// Throws std::invalid_argument for bad options (frame range, size, effect, output kind) and for an
// avatar none of whose joints is named like one of the clip's, BvhError for an unreadable file,
// GltfError for an avatar that cannot be read or has neither a skin nor morph targets, glc::GlError when no GL context
// can be made, std::runtime_error for output that cannot be written. Nothing is left at `out` on failure. Progress (a
// bar on a terminal) and a summary go to `log`.
void run_render(const RenderCommand& command, std::FILE* log);

}  // namespace performer::cli
