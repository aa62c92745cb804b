#pragma once
#include <memory>

#include "dwt/backend.h"
#include "base/thread_pool.h"

namespace dwt_cpu {

// Lifting on the CPU: every kernel, every boundary scheme; exact integers for the reversible 5/3.
// Per level: vertical then horizontal (T.800 F.4.2's 2D_SD order, which matters for the rounding of
// the reversible kernel), inverse in the mirror order.
class CpuBackend final : public dwt::DwtBackend {
 public:
  explicit CpuBackend(int threads = 0);  // 0: one per hardware thread
  // Runs on the caller's pool (which must outlive the backend), so that one program keeps one set
  // of worker threads for every stage.
  explicit CpuBackend(base::ThreadPool& pool);

  std::string name() const override;
  bool supports(dwt::KernelId kernel) const override;
  int threads() const { return pool_->size(); }

  void forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void forward(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;
  // The same transforms on 64-bit planes, for samples of more than 31 bits (T.800 allows 38, and
  // the transform adds bits): the reversible 5/3 exact on int64, the float kernels in double.
  // Not through DwtBackend: only the CPU computes them.
  void forward(dwt::PlaneSpan<double> plane, const dwt::DwtParams& params);
  void inverse(dwt::PlaneSpan<double> plane, const dwt::DwtParams& params);
  void forward(dwt::PlaneSpan<std::int64_t> plane, const dwt::DwtParams& params);
  void inverse(dwt::PlaneSpan<std::int64_t> plane, const dwt::DwtParams& params);

 private:
  template <class T>
  void transform(dwt::PlaneSpan<T> plane, const dwt::DwtParams& params, bool inverse);

  std::unique_ptr<base::ThreadPool> owned_pool_;
  base::ThreadPool* pool_;
};

}  // namespace dwt_cpu
