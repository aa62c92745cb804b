// What `performer pose` and `performer render` share: the frame range check and the whole
// performer they pose (the body grown around the BVH's skeleton, the procedural head on its head
// joint).
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

}  // namespace performer::cli
