#pragma once
// Hand-made skeletons for performer tests that must run without the motion capture assets.
#include <string>

#include <glm/vec3.hpp>

#include "performer/skeleton.h"

namespace test_support {

// A joint with no channels: only its place in the hierarchy and its rest offset matter.
inline performer::Joint joint(const std::string& name, int parent, glm::vec3 offset, bool end_site = false) {
  performer::Joint j;
  j.name = name;
  j.parent = parent;
  j.offset = offset;
  j.end_site = end_site;
  return j;
}

}  // namespace test_support
