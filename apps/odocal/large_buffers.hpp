#pragma once

namespace odocal::cli {

// Buffers of 4 MiB and more are mapped on their own and go back to the system when freed.
// glibc's default raises that threshold to the size of each such buffer freed (up to 32 MiB),
// after which the batch's many buffers of a few MiB come from the heap, which keeps them: a
// 10-hour log's peak resident memory 7 % higher (docs/batch-calibration.md). No effect without
// glibc's allocator (a sanitizer's).
void return_large_buffers_to_the_system();

}  // namespace odocal::cli
