// The command line's allocator policy (apps/odocal/large_buffers.hpp): a buffer of a few MiB,
// freed, goes back to the system even after a larger one was freed before it, which under
// glibc's default would have raised the threshold and kept the smaller one in the heap.

#include "large_buffers.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "address_sanitizer.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

void* volatile sink = nullptr;  // keeps the compiler from eliding the allocations

[[maybe_unused]] void* touched(std::size_t bytes) {  // unused where the test skips
  void* memory = std::malloc(bytes);
  if (memory != nullptr) std::memset(memory, 1, bytes);
  sink = memory;
  return memory;
}

TEST(LargeBuffers, GoBackToTheSystemAfterALargerOneWasFreed) {
#if !defined(__GLIBC__) || defined(ODOCAL_UNDER_ADDRESS_SANITIZER)
  GTEST_SKIP() << "glibc's own allocator only";
#else
  odocal::cli::return_large_buffers_to_the_system();
  std::free(touched(24u << 20));
  const std::size_t mapped_before = mallinfo2().hblkhd;
  void* buffer = touched(8u << 20);
  ASSERT_NE(buffer, nullptr);
  EXPECT_GE(mallinfo2().hblkhd, mapped_before + (8u << 20)) << "mapped on its own";
  std::free(buffer);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "returned when freed";
#endif
}

}  // namespace
