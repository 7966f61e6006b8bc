#include "large_buffers.hpp"

#include <cstdlib>  // defines __GLIBC__ where it is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace odocal::cli {

void return_large_buffers_to_the_system() {
#if defined(__GLIBC__)
  constexpr int kMappedFromBytes = 4 << 20;
  mallopt(M_MMAP_THRESHOLD, kMappedFromBytes);  // a fixed threshold: no dynamic raise
#endif
}

}  // namespace odocal::cli
