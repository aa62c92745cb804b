#pragma once
#include "dwt/error.h"
#include "dwt/kernel.h"

namespace dwt_cpu {

// Integer lifting (rows and strips alike) is the reversible 5/3's alone.
inline void require_reversible(const dwt::Kernel& k) {
  if (k.id != dwt::KernelId::Reversible53) throw dwt::DwtError("integer planes need the reversible 5/3 kernel");
}

}  // namespace dwt_cpu
