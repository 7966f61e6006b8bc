#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace odocal::cli {

// Buffers of 4 MiB and more are mapped on their own and go back to the system when freed.
// glibc's default raises that threshold to the size of each such buffer freed (up to 32 MiB),
// after which the batch's many buffers of a few MiB come from the heap, which keeps them: a
// 10-hour log's peak resident memory 7 % higher (docs/batch-calibration.md). No effect without
// glibc's allocator (a sanitizer's).
void return_large_buffers_to_the_system();

// GLIBC_TUNABLES as `existing` with glibc's allocator told to ask for transparent huge pages
// (glibc.malloc.hugetlb=1), or nothing where `existing` already says how (a user's
// glibc.malloc.hugetlb=0 stands).
std::optional<std::string> tunables_with_huge_pages(const char* existing);

// Whether a tool watches this process through a preloaded library: run again, the program would
// leave the tool (valgrind cannot even start it so). valgrind leaves its library in LD_PRELOAD;
// heaptrack takes its own out of the environment once loaded, and only the files mapped into the
// process (`mapped_files`, as /proc/self/maps lists them) still show it.
bool preloaded_tool_watches(const char* ld_preload, std::string_view mapped_files);
// The same for this process.
bool preloaded_tool_watches();

// Runs this program again with those tunables where the environment does not yet say how, and no
// preloaded tool watches it (glibc reads them only at start-up), so that each buffer mapped on its
// own is backed by huge pages where the kernel grants them (transparent_hugepage: madvise or
// always): the batch maps and frees its buffers of a few MiB at every solve, and faulting them in 4
// KiB pages took a quarter of the 10-hour drive's processor time (docs/batch-calibration.md,
// "Memory and time"). Returns where it does not run again (not glibc, or the exec failed).
void map_large_buffers_on_huge_pages(char** argv);

}  // namespace odocal::cli
