#include "gltf_accessor.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "performer/gltf_skin.h"

namespace performer::detail {

namespace {

// Beyond this an accessor is taken as corrupt rather than allocated (a sparse accessor without a
// buffer view has no bytes to bound its count).
constexpr std::size_t kMaxElements = std::size_t{1} << 28;

int component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);  // glTF is little-endian, as is every machine this builds for
  return v;
}

// One component, decoded; `normalized` maps integers to [0, 1] (unsigned) or [-1, 1] (signed).
double decode(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<std::uint32_t>(p);
    default:
      return load<float>(p);
  }
}

// The bytes of buffer view `view` from `offset` on, checked to hold `count` elements of
// `element_size` bytes spaced `stride` apart.
const unsigned char* view_bytes(const tinygltf::Model& model, int view, std::size_t offset, std::size_t count,
                                std::size_t element_size, std::size_t stride, const std::string& file,
                                const std::string& what) {
  if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size())
    throw GltfError(file, what + ": buffer view " + std::to_string(view) + " does not exist");
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(view)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
    throw GltfError(file, what + ": buffer " + std::to_string(bv.buffer) + " does not exist");
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    throw GltfError(file, what + ": buffer view " + std::to_string(view) + " lies outside its buffer");
  if (count == 0) return data.data();
  // Last element's end = offset + stride * (count - 1) + element_size, computed without overflow.
  const std::size_t length = bv.byteLength;
  if (offset > length || element_size > length - offset || (count - 1) > (length - offset - element_size) / stride)
    throw GltfError(file,
                    what + ": " + std::to_string(count) + " elements overrun buffer view " + std::to_string(view));
  return data.data() + bv.byteOffset + offset;
}

}  // namespace

AccessorValues read_accessor(const tinygltf::Model& model, int index, int type, std::initializer_list<int> allowed,
                             const std::string& file, const std::string& what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    throw GltfError(file, what + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.type != type)
    throw GltfError(file, what + ": accessor " + std::to_string(index) + " has the wrong element type");
  if (std::find(allowed.begin(), allowed.end(), a.componentType) == allowed.end())
    throw GltfError(file, what + ": accessor " + std::to_string(index) + " has component type " +
                              std::to_string(a.componentType) + ", not allowed here");
  if (a.count > kMaxElements) throw GltfError(file, what + ": accessor " + std::to_string(index) + " is too large");

  AccessorValues out;
  out.count = a.count;
  out.components = type_components(type);
  const auto components = static_cast<std::size_t>(out.components);
  const auto size = static_cast<std::size_t>(component_size(a.componentType));
  const std::size_t element_size = size * components;
  out.values.assign(out.count * components, 0.0);  // no buffer view: zeros, as the specification says

  auto read_elements = [&](const unsigned char* base, std::size_t stride, std::size_t count, auto&& target) {
    for (std::size_t e = 0; e < count; ++e)
      for (std::size_t c = 0; c < components; ++c)
        out.values[target(e) * components + c] = decode(base + e * stride + c * size, a.componentType, a.normalized);
  };
  if (a.bufferView >= 0) {
    if (static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
      throw GltfError(file, what + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    const std::size_t stride = bv.byteStride == 0 ? element_size : bv.byteStride;
    if (stride < element_size)
      throw GltfError(file, what + ": byte stride " + std::to_string(stride) + " is shorter than an element");
    const unsigned char* base =
        view_bytes(model, a.bufferView, a.byteOffset, a.count, element_size, stride, file, what);
    read_elements(base, stride, a.count, [](std::size_t e) { return e; });
  }
  if (a.sparse.isSparse && a.sparse.count > 0) {
    const auto count = static_cast<std::size_t>(a.sparse.count);
    if (count > a.count) throw GltfError(file, what + ": more sparse values than elements");
    const int index_type = a.sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      throw GltfError(file, what + ": sparse indices have component type " + std::to_string(index_type));
    const auto index_size = static_cast<std::size_t>(component_size(index_type));
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
      throw GltfError(file, what + ": negative sparse byte offset");
    const unsigned char* indices =
        view_bytes(model, a.sparse.indices.bufferView, static_cast<std::size_t>(a.sparse.indices.byteOffset), count,
                   index_size, index_size, file, what + " sparse indices");
    const unsigned char* values =
        view_bytes(model, a.sparse.values.bufferView, static_cast<std::size_t>(a.sparse.values.byteOffset), count,
                   element_size, element_size, file, what + " sparse values");
    read_elements(values, element_size, count, [&](std::size_t e) {
      const auto target = static_cast<std::size_t>(decode(indices + e * index_size, index_type, false));
      if (target >= out.count)
        throw GltfError(
            file, what + ": sparse index " + std::to_string(target) + " of " + std::to_string(out.count) + " elements");
      return target;
    });
  }
  return out;
}

}  // namespace performer::detail
