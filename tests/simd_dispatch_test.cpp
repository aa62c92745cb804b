// simd_dispatch answers as libhwy.so would: the same supported targets, so every vectorised kernel
// runs the same code as with Highway's own library, and never one the machine cannot execute.
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <hwy/highway.h>

#include <cstdint>

namespace {

// Highway's own answer, from its shared library loaded beside ours (dlsym on its handle finds its
// definition, not simd_dispatch's, which this executable does not export).
struct LibHwy {
  void* handle = dlopen("libhwy.so.1", RTLD_NOW | RTLD_LOCAL);
  ~LibHwy() {
    if (handle) dlclose(handle);
  }
  std::int64_t supported_targets() const {
    using Fn = std::int64_t (*)();
    auto fn = reinterpret_cast<Fn>(dlsym(handle, "_ZN3hwy16SupportedTargetsEv"));
    return fn ? fn() : -1;
  }
};

// The targets Highway 1.0.3 knows on this architecture (HWY_TARGETS lists the compiled ones).
constexpr std::int64_t kKnownTargets =
    HWY_AVX3_DL | HWY_AVX3 | HWY_AVX2 | HWY_SSE4 | HWY_SSSE3 | HWY_EMU128 | HWY_SCALAR;

TEST(SimdDispatch, SupportedTargetsAgreeWithLibhwy) {
  const LibHwy lib;
  if (!lib.handle) GTEST_SKIP() << "libhwy.so.1 is not installed (Debian libhwy1): no reference to compare with";
  const std::int64_t theirs = lib.supported_targets();
  ASSERT_NE(theirs, -1) << "libhwy.so.1 has no hwy::SupportedTargets()";
  EXPECT_EQ(hwy::SupportedTargets() & kKnownTargets, theirs & kKnownTargets)
      << std::hex << "ours 0x" << hwy::SupportedTargets() << ", libhwy's 0x" << theirs;
}

TEST(SimdDispatch, FallbacksAlwaysSupported) {
  EXPECT_NE(hwy::SupportedTargets() & HWY_SCALAR, 0);
  EXPECT_NE(hwy::SupportedTargets() & HWY_EMU128, 0);
}

}  // namespace
