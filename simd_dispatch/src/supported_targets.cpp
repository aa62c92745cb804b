// hwy::SupportedTargets and hwy::GetChosenTarget, the two functions Highway's HWY_EXPORT /
// HWY_DYNAMIC_DISPATCH tables call, so that no program of ours loads libhwy.so (CMakeLists.txt:
// its static initialiser costs every process about 4 ms).
//
// A target is supported when the processor reports every instruction-set extension its code may
// use and the operating system saves the registers it uses. The extension lists are the ones
// Highway 1.0.3 documents for each x86 target (hwy/detect_targets.h and its targets.cc); the CPUID
// bit positions are Intel's (SDM volume 2A, CPUID: leaf 1 ECX/EDX, leaf 7 EBX/ECX, leaf 0x80000001
// ECX) and the XCR0 state bits Intel's (SDM volume 1, 13.3). tests/simd_dispatch_test.cpp checks the
// result against libhwy.so's own on the machine that runs it.
#include <hwy/highway.h>

#include <cstdint>

#if HWY_ARCH_X86
#include <cpuid.h>
#endif

namespace {

#if HWY_ARCH_X86

struct Registers {
  std::uint32_t eax = 0, ebx = 0, ecx = 0, edx = 0;
};

Registers cpuid(std::uint32_t leaf) {
  Registers r;
  // __get_cpuid_count returns 0 for a leaf above the processor's highest: all flags then stay 0.
  __get_cpuid_count(leaf, 0, &r.eax, &r.ebx, &r.ecx, &r.edx);
  return r;
}

bool bit(std::uint32_t reg, int index) { return ((reg >> index) & 1u) != 0; }

// XCR0, the register state the operating system saves on a context switch. Only readable (XGETBV)
// when CPUID.1:ECX.OSXSAVE says the system enabled XSAVE.
std::uint32_t os_saved_state() {
  std::uint32_t low = 0, high = 0;
  __asm__ volatile("xgetbv" : "=a"(low), "=d"(high) : "c"(0));
  return low;
}

std::int64_t x86_targets() {
  const Registers basic = cpuid(1), extended = cpuid(7), amd = cpuid(0x80000001u);

  const bool sse = bit(basic.edx, 25) && bit(basic.edx, 26);                                   // SSE, SSE2
  const bool ssse3 = sse && bit(basic.ecx, 0) && bit(basic.ecx, 9);                            // SSE3, SSSE3
  const bool sse4 = ssse3 && bit(basic.ecx, 19) && bit(basic.ecx, 20) && bit(basic.ecx, 1) &&  // 4.1, 4.2, CLMUL
                    bit(basic.ecx, 25);                                                        // AES
  const bool avx2_isa = sse4 && bit(basic.ecx, 28) && bit(extended.ebx, 5) &&                  // AVX, AVX2
                        bit(basic.ecx, 29) && bit(basic.ecx, 12) &&                            // F16C, FMA
                        bit(extended.ebx, 3) && bit(extended.ebx, 8) &&                        // BMI1, BMI2
                        bit(amd.ecx, 5);                                                       // LZCNT
  const bool avx3_isa = avx2_isa && bit(extended.ebx, 16) && bit(extended.ebx, 17) &&          // AVX-512 F, DQ
                        bit(extended.ebx, 30) && bit(extended.ebx, 31);                        // BW, VL
  const bool avx3_dl_isa = avx3_isa && bit(extended.ecx, 11) && bit(extended.ecx, 10) &&       // VNNI, VPCLMULQDQ
                           bit(extended.ecx, 1) && bit(extended.ecx, 6) &&                     // VBMI, VBMI2
                           bit(extended.ecx, 9) && bit(extended.ecx, 14) &&                    // VAES, VPOPCNTDQ
                           bit(extended.ecx, 12);                                              // BITALG

  // The vector registers' upper parts survive a context switch only where the system saves them:
  // SSE and AVX state (XCR0 bits 1, 2) for 256-bit vectors, the opmask and both halves of the
  // 512-bit registers (bits 5, 6, 7) for AVX-512.
  const std::uint32_t saved = bit(basic.ecx, 27) ? os_saved_state() : 0;
  const bool ymm = bit(saved, 1) && bit(saved, 2);
  const bool zmm = ymm && bit(saved, 5) && bit(saved, 6) && bit(saved, 7);

  std::int64_t targets = 0;
  if (ssse3) targets |= HWY_SSSE3;
  if (sse4) targets |= HWY_SSE4;
  if (avx2_isa && ymm) targets |= HWY_AVX2;
  if (avx3_isa && zmm) targets |= HWY_AVX3;
  if (avx3_dl_isa && zmm) targets |= HWY_AVX3_DL;
  return targets;
}

#endif

std::int64_t detect_targets() {
  // The portable fallbacks run everywhere.
  std::int64_t targets = HWY_SCALAR | HWY_EMU128;
#if HWY_ARCH_X86
  targets |= x86_targets();
#else
  // Elsewhere only what the compiler was told the machine has.
  targets |= HWY_ENABLED_BASELINE;
#endif
  return targets;
}

}  // namespace

namespace hwy {

std::int64_t SupportedTargets() {
  static const std::int64_t targets = detect_targets();
  return targets;
}

ChosenTarget& GetChosenTarget() {
  static ChosenTarget chosen;
  return chosen;
}

}  // namespace hwy
