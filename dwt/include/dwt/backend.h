#pragma once
#include <cstdint>
#include <string>

#include "dwt/params.h"
#include "dwt/plane.h"

namespace dwt {

// One interface, two implementations (dwt_cpu: lifting; dwt_gpu: the thesis' fragment-shader
// convolution). Both transform in place into the Mallat layout: after `levels` levels the plane
// holds LL of the coarsest level top-left and HL/LH/HH of each level around it (see band_rect).
// Float kernels run on float planes; the reversible 5/3 needs int32 planes.
class DwtBackend {
 public:
  virtual ~DwtBackend() = default;

  virtual std::string name() const = 0;  // one line, e.g. "cpu lifting (AVX2, 2 threads)"
  virtual bool supports(KernelId kernel) const = 0;

  virtual void forward(PlaneSpan<float> plane, const DwtParams& params) = 0;
  virtual void inverse(PlaneSpan<float> plane, const DwtParams& params) = 0;
  virtual void forward(PlaneSpan<std::int32_t> plane, const DwtParams& params) = 0;
  virtual void inverse(PlaneSpan<std::int32_t> plane, const DwtParams& params) = 0;
};

}  // namespace dwt
