// The command line runs itself again with glibc's allocator asking for transparent huge pages
// (apps/odocal/large_buffers.hpp). This executable does what the command line's main does before
// its tests run, so the tests see the process as the command line would.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include "address_sanitizer.hpp"
#include "large_buffers.hpp"

namespace {

using odocal::cli::tunables_with_huge_pages;

TEST(HugePages, TunablesAreAddedToWhatTheUserSet) {
  EXPECT_EQ(tunables_with_huge_pages(nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_pages(""), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.check=3"),
            "glibc.malloc.check=3:glibc.malloc.hugetlb=1");
}

TEST(HugePages, AUsersOwnChoiceStands) {
  EXPECT_FALSE(tunables_with_huge_pages("glibc.malloc.hugetlb=0"));
  EXPECT_FALSE(tunables_with_huge_pages("glibc.malloc.check=3:glibc.malloc.hugetlb=2"));
}

TEST(HugePages, AProcessThatAPreloadedToolWatchesIsNotRunAgain) {
  using odocal::cli::preloaded_tool_watches;
  const std::string_view plain =
      "55d0c8a00000-55d0c8a2a000 r--p 00000000 08:01 1234 /usr/bin/odocal\n"
      "7f3a1c000000-7f3a1c022000 r--p 00000000 08:01 5678 /usr/lib/x86_64-linux-gnu/libc.so.6\n";
  EXPECT_TRUE(preloaded_tool_watches("/usr/libexec/valgrind/vgpreload_core-amd64-linux.so", plain));
  EXPECT_FALSE(preloaded_tool_watches(nullptr, plain));
  EXPECT_FALSE(preloaded_tool_watches("", plain));
  // heaptrack (1.4, Debian 12) has taken its library out of LD_PRELOAD by the time main runs.
  const std::string heaptrack = std::string(plain) +
                                "7f3a1c400000-7f3a1c41e000 r-xp 00000000 08:01 91011 "
                                "/usr/lib/heaptrack/libheaptrack_preload.so\n";
  EXPECT_TRUE(preloaded_tool_watches(nullptr, heaptrack));
  // This process's own maps name no tool's library (a test run under valgrind says so above).
  if (std::getenv("LD_PRELOAD") == nullptr) {
    EXPECT_FALSE(preloaded_tool_watches());
  }
}

TEST(HugePages, TheProgramRunsWithTheTunableSet) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "glibc only";
#else
  if (odocal::cli::preloaded_tool_watches())
    GTEST_SKIP() << "a preloaded tool watches this process: not run again";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  ASSERT_NE(tunables, nullptr);
  EXPECT_NE(std::string(tunables).find("glibc.malloc.hugetlb"), std::string::npos);
#endif
}

// The kernel's transparent huge page mode: "always", "madvise" or "never" (the bracketed one).
[[maybe_unused]] std::string transparent_huge_pages_mode() {  // unused where the test skips
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(file, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos
             ? ""
             : line.substr(open + 1, close - open - 1);
}

// AnonHugePages of the mapping that holds `address`, in kB (-1: not found).
[[maybe_unused]] long huge_pages_kb_at(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= at && at < end;
      continue;
    }
    if (inside && line.rfind("AnonHugePages:", 0) == 0)
      return std::stol(line.substr(std::strlen("AnonHugePages:")));
  }
  return -1;
}

[[maybe_unused]] void* volatile sink = nullptr;  // keeps the compiler from eliding the allocation

TEST(HugePages, ALargeBufferIsBackedByHugePages) {
#if !defined(__GLIBC__) || defined(ODOCAL_UNDER_ADDRESS_SANITIZER)
  GTEST_SKIP() << "glibc's own allocator only";
#else
  const std::string mode = transparent_huge_pages_mode();
  if (mode != "always" && mode != "madvise")
    GTEST_SKIP() << "the kernel grants no transparent huge pages (mode '" << mode << "')";
  if (const char* set = std::getenv("GLIBC_TUNABLES");
      set != nullptr && std::string(set).find("glibc.malloc.hugetlb=0") != std::string::npos)
    GTEST_SKIP() << "GLIBC_TUNABLES asks for none";
  odocal::cli::return_large_buffers_to_the_system();
  constexpr std::size_t kBytes = 64u << 20;
  void* buffer = std::malloc(kBytes);
  ASSERT_NE(buffer, nullptr);
  std::memset(buffer, 1, kBytes);
  sink = buffer;
  const long huge_kb = huge_pages_kb_at(static_cast<char*>(buffer) + kBytes / 2);
  std::free(buffer);
  EXPECT_GT(huge_kb, 0) << "a 64 MiB buffer, mapped on its own, faulted in 4 KiB pages only";
#endif
}

}  // namespace

int main(int argc, char** argv) {
  odocal::cli::map_large_buffers_on_huge_pages(argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
