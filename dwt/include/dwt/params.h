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
};

// Throws DwtError naming the problem: empty plane, negative origin, more levels than the plane
// allows (see max_levels), or a level count over the 32 that T.800 permits.
void validate(const DwtParams& p, int width, int height);

}  // namespace dwt
