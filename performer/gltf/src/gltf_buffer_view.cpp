#include "gltf_buffer_view.h"

#include <vector>

namespace performer::detail {

int append_buffer_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  buffer.resize((buffer.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = size;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(bytes);
  buffer.insert(buffer.end(), p, p + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

}  // namespace performer::detail
