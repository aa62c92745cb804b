#include "imageio/plane_memory.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>

namespace imageio {

void prefer_huge_pages(const void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHugePage = kHugePageBytes;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
  if (data == nullptr || last <= first) return;
  // Not for the largest planes: with the kernel's THP defrag set to "madvise" (Debian's default) a
  // hinted range is compacted synchronously when free huge pages run short, as they do right after
  // another large process exits. A 4096x4096 encode's 64 MiB planes then lost 0.2 s to compaction
  // (0.61 s against 0.42 s with ordinary pages) where 2048x2048's 16 MiB ones gain a few percent.
  // Kept although it has a cost on VMs that report free memory to their host (virtio-balloon free
  // page reporting, as on this project's 2-vCPU machines): the free 2 MiB blocks a hint takes are
  // then those handed back after about two seconds, and their first touch costs a fault in the host
  // too. On such a VM, 2048x2048 runs two seconds apart took 15-25 % longer with the hint (j2kenc
  // --ht at 0.75 bpp 0.229 s against 0.196 s, a 0.75 bpp j2kdec 0.204 against 0.152 s), while runs
  // straight after one another, or repeated work in one process, took about 10 % less (EBCOT at
  // 0.75 bpp 0.173 against 0.195 s, j2kdec 0.100 against 0.110 s): blocks just freed are still the
  // guest's. Without free page reporting (bare metal) huge pages cost no more than ordinary ones.
  // Measured 2026-11-28; the fourteenth session's README paragraph has the numbers.
  constexpr std::size_t kLargestHinted = std::size_t{32} << 20;
  if (bytes > kLargestHinted) return;
  // Failure (no THP support, EINVAL on old kernels) only means ordinary pages: ignored.
  (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

bool populate_for_writing(const void* data, std::size_t bytes) {
#ifdef MADV_POPULATE_WRITE
  if (data == nullptr || bytes == 0) return true;
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = begin / page * page;
  return ::madvise(reinterpret_cast<void*>(first), begin + bytes - first, MADV_POPULATE_WRITE) == 0;
#else
  (void)data;
  (void)bytes;
  return false;
#endif
}

void discard_pages(const void* data, std::size_t bytes) {
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + page - 1) / page * page, last = (begin + bytes) / page * page;
  // Failure leaves the pages in place, to be freed with their allocation: nothing is lost.
  if (data != nullptr && last > first) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
}

}  // namespace imageio
