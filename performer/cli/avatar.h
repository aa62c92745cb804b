// `performer avatar`: the generated performer (the body grown around a BVH file's skeleton, the
// procedural head on its head joint) written as a glTF 2.0 avatar, in metres: one skinned mesh whose
// joints are the skeleton's, with the face's targets as named morph targets. It opens in glTF
// viewers, and `performer render --gltf` takes it back: an avatar made by our own code, for tests
// and examples, with no downloaded model.
#pragma once

#include <cstdio>
#include <filesystem>

namespace performer::cli {

struct AvatarCommand {
  std::filesystem::path bvh;
  std::filesystem::path out;  // .glb (binary) or .gltf (JSON with the buffer embedded)
  unsigned threads = 0;       // 0: all hardware threads
};

// Throws std::invalid_argument for an output that is not .glb or .gltf, BvhError for an unreadable
// file, as build_character does, GltfError when the file cannot be written (nothing is left then).
void run_avatar(const AvatarCommand& command, std::FILE* log);

}  // namespace performer::cli
