#pragma once
#include "dwt/boundary.h"
#include "dwt/geometry.h"
#include "dwt/kernel.h"

namespace dwt {

struct DwtParams {
  KernelId kernel = KernelId::Irreversible97;
  Boundary boundary = Boundary::Symmetric;
  int levels = 5;
  Origin origin{};
  // JPEG 2000 applies a codestream's level count to every tile, and an edge tile can be a single
  // sample wide; its further levels just pass lone samples along (T.800 F.4.7). The codec sets
  // this; tools that transform one plane keep the stricter check.
  bool levels_may_exceed_size = false;
};

// Throws DwtError naming the problem: empty plane, negative origin, a level count over the 32 that
// T.800 permits, or (unless levels_may_exceed_size) more levels than the plane allows (max_levels).
void validate(const DwtParams& p, int width, int height);

}  // namespace dwt
