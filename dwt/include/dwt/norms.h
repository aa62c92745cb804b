#pragma once
#include "dwt/geometry.h"
#include "dwt/kernel.h"

namespace dwt {

// L2 norm of the 1-D synthesis basis function of one coefficient of the low (high = false) or high
// band at decomposition level `level` (1 = finest), reconstructed to full resolution. Computed from
// the kernel's own lifting network, so it holds for any kernel and normalisation. A coefficient
// error e in that band becomes an image-domain squared error of e^2 * norm^2.
double synthesis_norm_1d(const Kernel& kernel, int level, bool high);

// The 2-D norm of a subband: the product of its horizontal and vertical 1-D norms. LL is the
// coarsest level's low-pass band in both directions.
double synthesis_norm(const Kernel& kernel, int level, Orientation orientation);

}  // namespace dwt
