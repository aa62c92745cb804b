// Building glTF files: raw little-endian bytes appended to the model's one buffer as a new buffer
// view, started on a 4-byte boundary so every accessor is aligned for its components as glTF
// requires (floats, uint32 and uint16 are stored as they are in memory on every machine this
// builds for). Shared by the face and skin writers. Private to the library.
#pragma once

#include <cstddef>

#include <tiny_gltf.h>

namespace performer::detail {

// Appends to model.buffers[0] (which must exist) and returns the new view's index. target:
// TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER or 0 (no target).
int append_buffer_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target);

}  // namespace performer::detail
