// Reading one glTF accessor into plain numbers, whatever its layout: any component type, strided
// buffer views, normalised integers, sparse substitution. Every offset is checked against the
// buffers, so a malformed file gives an error rather than a read out of bounds.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace performer::detail {

struct AccessorValues {
  std::size_t count = 0;       // elements
  int components = 0;          // values per element
  std::vector<double> values;  // count * components; normalised integers already mapped to [0, 1] or [-1, 1]
};

// Reads accessor `index`, which must have element type `type` (TINYGLTF_TYPE_*) and a component type
// among `allowed` (TINYGLTF_COMPONENT_TYPE_*). `what` names it in messages ("POSITION of mesh 0
// primitive 1"). Throws GltfError(file, ...) on any problem.
AccessorValues read_accessor(const tinygltf::Model& model, int index, int type, std::initializer_list<int> allowed,
                             const std::string& file, const std::string& what);

}  // namespace performer::detail
