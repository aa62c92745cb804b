#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace imageio {

// 2 MiB: the memory one page-table page maps on x86-64 (and the size of a transparent huge page).
inline constexpr std::size_t kHugePageBytes = std::size_t{1} << 21;

// An allocator whose elements start uninitialised, for planes that are written in full before they
// are read: their pages are first touched by the stage that fills them (in parallel where it is
// threaded), with no zero pass before. Blocks of 2 MiB or more start on a 2 MiB boundary, so that
// runs of 2 MiB faulted in by one thread each (the decoder's fault_in) fill whole page-table pages.
//
// No transparent huge pages are asked for (MADV_HUGEPAGE, used until 2026-11-28): on a VM that
// reports free memory to its host (virtio-balloon free page reporting, as on this project's 2-vCPU
// machines) the free 2 MiB blocks a hint takes are those handed back to the host, and their first
// touch costs a fault in the host too. Runs two seconds apart, 2048x2048, 2 threads: j2kenc --ht at
// 0.75 bpp took 0.196 s without the hint against 0.229 s with it, EBCOT 0.221 against 0.266 s, a
// 0.75 bpp j2kdec 0.152 against 0.204 s (shift + ICT alone 18-28 ms against 9-120 ms). Only runs
// straight after one another, on blocks just freed, were faster with it (EBCOT 0.173 s against 0.195 s).
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) < kHugePageBytes) return std::allocator<T>::allocate(n);
    return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{kHugePageBytes}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < kHugePageBytes)
      std::allocator<T>::deallocate(p, n);
    else
      // The unsized form: Clang does not declare sized deallocation unless asked
      // (-fsized-deallocation), and the fuzz build compiles this header with Clang.
      ::operator delete (p, std::align_val_t{kHugePageBytes});
  }
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// One plane of integer samples, row by row (PlanarImage, and the encoder's source components).
using SamplePlane = std::vector<std::int32_t, UninitialisedAllocator<std::int32_t>>;

}  // namespace imageio
