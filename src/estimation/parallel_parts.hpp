#pragma once
// A loop over independent items split into contiguous parts, one thread each (the batch's
// pre-integration of a long drive: docs/batch-calibration.md, "Memory and time"). Each part
// writes only its own items and its own tally, so the result is the same on any number of
// threads, to the last bit.

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace odocal::batch {

// Threads for `requested` (0: one per core the machine reports; never fewer than one).
inline int usable_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Below this many items per part a thread costs more than it saves.
inline constexpr std::size_t kMinItemsPerPart = 256;

// Calls work(part, begin, end) for `parts` contiguous ranges [begin, end) that cover [0, count)
// in order, the first on the calling thread; returns the number of parts used (at most
// `threads`). The first exception a part throws is thrown here once every part has ended.
template <class Work>
std::size_t run_in_parts(std::size_t count, int threads, const Work& work) {
  const std::size_t parts = std::clamp<std::size_t>(count / kMinItemsPerPart, 1,
                                                    static_cast<std::size_t>(std::max(threads, 1)));
  std::vector<std::exception_ptr> failures(parts);
  const auto part = [&](std::size_t p) {
    try {
      work(p, count * p / parts, count * (p + 1) / parts);
    } catch (...) {
      failures[p] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> helpers;
    helpers.reserve(parts - 1);
    for (std::size_t p = 1; p < parts; ++p) helpers.emplace_back(part, p);
    part(0);
  }  // joined
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
  return parts;
}

}  // namespace odocal::batch
