// What `performer pose`, `performer render` and `performer avatar` share: the frame range check and
// the whole performer they pose (the body grown around the BVH's skeleton, the procedural head or
// another face on its head joint).
#pragma once

#include <filesystem>

#include "performer/bvh.h"
#include "performer/character.h"
#include "performer/face_model.h"

namespace performer::cli {

// Throws std::invalid_argument, naming the file and its frames, unless 0 <= first <= last < frames.
void check_frame_range(const Bvh& bvh, const std::filesystem::path& file, int first, int last);

struct CliCharacter {
  FaceModel face;  // the head's targets, which weight tracks bind to
  Character character;
};

CliCharacter build_cli_character(const Skeleton& skeleton, unsigned threads);
// The same with another face on the head joint (a face model in metres, +Y up, facing +Z, as the
// procedural head and glTF files are), and the whole character in skeleton units times
// `output_scale` (BodyMeshParams::output_scale).
CliCharacter build_cli_character(const Skeleton& skeleton, unsigned threads, FaceModel face, float output_scale = 1.0f);

}  // namespace performer::cli
