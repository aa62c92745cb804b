#include "dwt_cpu/cpu_backend.h"

#include <string>
#include <type_traits>

#include "axis_pass.h"
#include "dwt/error.h"
#include "lifting_simd.h"

namespace dwt_cpu {

CpuBackend::CpuBackend(int threads)
    : owned_pool_(std::make_unique<base::ThreadPool>(threads)), pool_(owned_pool_.get()) {}

CpuBackend::CpuBackend(base::ThreadPool& pool) : pool_(&pool) {}

std::string CpuBackend::name() const {
  return std::string("cpu lifting (") + simd::target_name() + ", " + std::to_string(pool_->size()) + " threads)";
}

bool CpuBackend::supports(dwt::KernelId) const { return true; }

template <class T>
void CpuBackend::transform(dwt::PlaneSpan<T> plane, const dwt::DwtParams& params, bool inverse) {
  dwt::validate(params, plane.width, plane.height);
  const dwt::Kernel& kernel = dwt::get_kernel(params.kernel);
  if (std::is_integral_v<T> != kernel.reversible)
    throw dwt::DwtError(std::string("the ") + std::string(kernel.description) +
                        (kernel.reversible ? " kernel transforms integer planes" : " kernel transforms float planes"));
  const auto levels = dwt::decomposition(plane.width, plane.height, params.origin, params.levels);
  auto pass = [&](const dwt::LevelGeometry& g, Axis axis) {
    const AxisPass p{kernel, params.boundary, axis, axis == Axis::Horizontal ? g.x : g.y, g.x.length, g.y.length};
    if (inverse)
      run_inverse<T>(p, plane, *pool_);
    else
      run_forward<T>(p, plane, *pool_);
  };
  if (!inverse) {
    for (const auto& g : levels) {
      pass(g, Axis::Vertical);
      pass(g, Axis::Horizontal);
    }
  } else {
    for (auto it = levels.rbegin(); it != levels.rend(); ++it) {
      pass(*it, Axis::Horizontal);
      pass(*it, Axis::Vertical);
    }
  }
}

void CpuBackend::forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) { transform(plane, params, false); }
void CpuBackend::inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) { transform(plane, params, true); }
void CpuBackend::forward(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) {
  transform(plane, params, false);
}
void CpuBackend::inverse(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) {
  transform(plane, params, true);
}

void CpuBackend::forward(dwt::PlaneSpan<double> plane, const dwt::DwtParams& params) {
  transform(plane, params, false);
}
void CpuBackend::inverse(dwt::PlaneSpan<double> plane, const dwt::DwtParams& params) { transform(plane, params, true); }
void CpuBackend::forward(dwt::PlaneSpan<std::int64_t> plane, const dwt::DwtParams& params) {
  transform(plane, params, false);
}
void CpuBackend::inverse(dwt::PlaneSpan<std::int64_t> plane, const dwt::DwtParams& params) {
  transform(plane, params, true);
}

}  // namespace dwt_cpu
