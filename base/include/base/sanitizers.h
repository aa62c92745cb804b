#pragma once
// GPUJ2K_ADDRESS_SANITIZER is defined in code built under AddressSanitizer, whichever the compiler:
// GCC defines __SANITIZE_ADDRESS__, Clang (which does not) answers __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define GPUJ2K_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GPUJ2K_ADDRESS_SANITIZER 1
#endif
#endif
