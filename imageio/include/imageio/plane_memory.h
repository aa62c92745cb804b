#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace imageio {

// The size of a transparent huge page on x86-64 (and of the alignment that lets one back memory).
inline constexpr std::size_t kHugePageBytes = std::size_t{1} << 21;

// An allocator whose elements start uninitialised, for planes that are written in full before they
// are read: their pages are first touched by the stage that fills them (in parallel where it is
// threaded), with no zero pass before. Blocks of 2 MiB or more start on a 2 MiB boundary, so that
// prefer_huge_pages can cover all of them: malloc's page-aligned 16 MiB plane left its first and
// last partial 2 MiB, 1,500 ordinary pages over an RGB image's three planes, to 4 KiB faults.
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

// Asks the kernel to back the 2 MiB-aligned part of [data, data + bytes) with transparent huge
// pages, before anything touches it. A 2048x2048 plane of 32-bit samples is 4096 ordinary pages:
// the first touch of each costs a fault and a page clear, some 30 ms for an RGB image's planes
// spread over the stages that fill them, where 2 MiB pages take a handful of faults. Only a hint:
// where the system does not offer huge pages (or the range holds no aligned 2 MiB) nothing changes,
// and ranges over 32 MiB are left alone (plane_memory.cpp: synchronous compaction).
void prefer_huge_pages(const void* data, std::size_t bytes);

// Faults in the pages that [data, data + bytes) touches, for writing, in one call where the kernel
// has MADV_POPULATE_WRITE (Linux 5.14), instead of a fault per page at the first store: on the
// project's 2-vCPU VMs a first-touch fault costs some 3 us, a populated page a quarter less (the
// 192 MiB of a 4096x4096 RGB encode's new planes, 15-20 ms less on 2 threads). False where the
// call is missing or refused: the pages then fault as they are first written.
bool populate_for_writing(const void* data, std::size_t bytes);

// Hands the pages wholly inside [data, data + bytes) back to the system (MADV_DONTNEED): they read
// as zeros afterwards, and the partial pages at either end are left as they are. For memory whose
// contents are no longer needed: rows already consumed, or a plane about to be freed, whose pages
// several threads discarding chunks of it free in parallel where the one munmap of its release
// would free them on one thread (the mapping's lock is shared for this, not for munmap).
void discard_pages(const void* data, std::size_t bytes);

// Sizes an empty vector to `n` elements through prefer_huge_pages: capacity first, the hint,
// then the elements (value-initialised, or left as they are by an allocator that does so).
template <class T, class Allocator>
void resize_with_huge_pages(std::vector<T, Allocator>& v, std::size_t n) {
  v.reserve(n);
  prefer_huge_pages(v.data(), n * sizeof(T));
  v.resize(n);
}

}  // namespace imageio
