#pragma once
// Run-time dispatch for scalar code, beside Highway's for vector code: GPUJ2K_X86_64_V3_CLONES in a
// function's attribute list, [[gnu::flatten, GPUJ2K_X86_64_V3_CLONES]], has GCC build the function
// twice, for the baseline x86-64 and for x86-64-v3, and pick one when the program is loaded
// (target_clones, an ifunc). It pays in branchy bit-twiddling code (the block coders' passes):
// BMI2's shifts by a register need no flags, LZCNT counts leading zeros without a test for 0, ANDN
// saves a move. Only the function itself and what is inlined into it are built for x86-64-v3: a
// function it calls stays built for the baseline, so no code that other callers share can need
// an instruction the processor lacks. `flatten` beside it inlines its callees into each clone.
// Elsewhere (Clang, other architectures) it is empty and the function is built once, and so it is
// under AddressSanitizer (GCC defines __SANITIZE_ADDRESS__): the clones are one source built for
// two targets, and with the sanitizers building both took twice as long for the build's slowest
// objects (the EBCOT block decoder's passes: 97 s against 45 s at -O1 on a 2-vCPU VM), so the
// sanitizer build tests the baseline clone's code alone.
// A clone must not let an exception out: with GCC 12 a throw inside one, or from anything it calls,
// ends the program (std::terminate) instead of unwinding to the caller's handler (checked with a
// two-line function, internal and external linkage alike). Code that can meet malformed input
// returns what went wrong and its caller throws (the HT block decoder's CleanupFault). The block
// encoders' clones grow byte vectors, so only running out of memory there throws (std::bad_alloc),
// and ends the program.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define GPUJ2K_X86_64_V3_CLONES gnu::target_clones("arch=x86-64-v3", "default")
#else
#define GPUJ2K_X86_64_V3_CLONES
#endif
