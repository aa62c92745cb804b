// `performer info`: what a BVH file holds, for a person deciding whether it suits the performer.
#pragma once

#include <cstdio>
#include <string>

#include "performer/bvh.h"

namespace performer::cli {

// Writes the report for `bvh` (read from `path`) to `out`.
void print_info(const Bvh& bvh, const std::string& path, std::FILE* out);

}  // namespace performer::cli
