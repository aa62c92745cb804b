#pragma once
#include <cstdint>
#include <string>

#include "dwt/params.h"
#include "dwt/plane.h"

namespace dwt {

// Wall-clock milliseconds of a device backend's last transform, split by stage (the thesis' Table
// 4.1 columns), measured with the device idle before each clock read so that its work is charged to
// the stage that issued it.
struct DeviceTimings {
  double context_ms = 0;   // creating the device context (only the first transform of a backend pays it)
  double compile_ms = 0;   // compiling and linking its programs (likewise once)
  double upload_ms = 0;    // buffers, tables and the plane to the device
  double compute_ms = 0;   // the transform itself
  double download_ms = 0;  // reading the plane back
  double total_ms() const { return context_ms + compile_ms + upload_ms + compute_ms + download_ms; }
};

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

  // A backend that moves planes to a device tells how its last transform's time split; null for
  // one that computes where the plane lies (all of its time is the transform).
  virtual const DeviceTimings* device_timings() const { return nullptr; }
};

}  // namespace dwt
