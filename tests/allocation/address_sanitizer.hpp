#pragma once
// ODOCAL_UNDER_ADDRESS_SANITIZER is defined where AddressSanitizer replaces glibc's allocator,
// whose policies the allocation tests check: gcc says so with a macro, clang with a feature test.

#if defined(__SANITIZE_ADDRESS__)
#define ODOCAL_UNDER_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ODOCAL_UNDER_ADDRESS_SANITIZER 1
#endif
#endif
