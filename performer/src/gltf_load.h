// Opening a glTF 2.0 file with tinygltf: binary (.glb) or JSON by its magic bytes rather than its
// name, images left undecoded (faces and skins need none, and an avatar's large or unsupported
// textures should neither cost time nor fail the load), and tinygltf's errors made one line.
// Shared by the face and skin readers. Private to the library.
#pragma once

#include <filesystem>

#include <tiny_gltf.h>

namespace performer::detail {

// Throws GltfError(file, ...) when the file cannot be opened or parsed.
tinygltf::Model load_gltf_model(const std::filesystem::path& path);

}  // namespace performer::detail
