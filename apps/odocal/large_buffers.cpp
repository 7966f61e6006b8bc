#include "large_buffers.hpp"

#include <unistd.h>

#include <cstdlib>  // defines __GLIBC__ where it is glibc
#include <fstream>
#include <iterator>
#include <string_view>

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

std::optional<std::string> tunables_with_huge_pages(const char* existing) {
  constexpr std::string_view kHugePages = "glibc.malloc.hugetlb=1";
  const std::string_view before = existing != nullptr ? existing : "";
  if (before.find("glibc.malloc.hugetlb") != std::string_view::npos) return std::nullopt;
  std::string tunables(before);
  if (!tunables.empty()) tunables += ':';
  tunables += kHugePages;
  return tunables;
}

bool preloaded_tool_watches(const char* ld_preload, std::string_view mapped_files) {
  if (ld_preload != nullptr && *ld_preload != '\0') return true;
  for (const std::string_view library : {"/libheaptrack_preload.so", "/vgpreload_"})
    if (mapped_files.find(library) != std::string_view::npos) return true;
  return false;
}

bool preloaded_tool_watches() {
  std::ifstream maps("/proc/self/maps");
  const std::string mapped_files{std::istreambuf_iterator<char>(maps),
                                 std::istreambuf_iterator<char>()};
  return preloaded_tool_watches(std::getenv("LD_PRELOAD"), mapped_files);
}

void map_large_buffers_on_huge_pages(char** argv) {
#if defined(__GLIBC__)
  const char* existing = std::getenv("GLIBC_TUNABLES");
  const std::optional<std::string> tunables = tunables_with_huge_pages(existing);
  if (!tunables || argv == nullptr || argv[0] == nullptr) return;
  // Read only where it would run again: the process it starts has the tunable set and stops above.
  if (preloaded_tool_watches()) return;
  const std::optional<std::string> before =
      existing != nullptr ? std::optional<std::string>(existing) : std::nullopt;
  if (setenv("GLIBC_TUNABLES", tunables->c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not run again (the exec failed): go on as started.
  if (before) {
    setenv("GLIBC_TUNABLES", before->c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
#else
  (void)argv;
#endif
}

}  // namespace odocal::cli
