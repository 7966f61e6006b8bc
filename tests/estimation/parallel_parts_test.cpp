// The batch's split of a loop into parts on threads: every item once, in contiguous parts in
// order, no more parts than threads or than the items support, and a part's exception thrown on
// the caller.

#include "estimation/parallel_parts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace odocal::batch {
namespace {

struct Part {
  std::size_t index, begin, end;
  std::thread::id thread;
};

std::vector<Part> parts_of(std::size_t count, int threads) {
  std::vector<Part> parts;
  std::mutex guard;
  const std::size_t used =
      run_in_parts(count, threads, [&](std::size_t p, std::size_t b, std::size_t e) {
        const std::lock_guard lock(guard);
        parts.push_back({p, b, e, std::this_thread::get_id()});
      });
  EXPECT_EQ(used, parts.size());
  std::sort(parts.begin(), parts.end(), [](auto& a, auto& b) { return a.index < b.index; });
  return parts;
}

TEST(ParallelParts, CoversEveryItemOnceInContiguousPartsInOrder) {
  const std::size_t count = 10 * kMinItemsPerPart + 7;
  const std::vector<Part> parts = parts_of(count, 3);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts.front().begin, 0u);
  EXPECT_EQ(parts.back().end, count);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    EXPECT_EQ(parts[p].index, p);
    EXPECT_LT(parts[p].begin, parts[p].end);
    if (p > 0) {
      EXPECT_EQ(parts[p].begin, parts[p - 1].end);
    }
  }
  // The first part runs on the caller, the others each on a thread of its own.
  EXPECT_EQ(parts[0].thread, std::this_thread::get_id());
  EXPECT_NE(parts[1].thread, parts[0].thread);
  EXPECT_NE(parts[2].thread, parts[1].thread);
}

TEST(ParallelParts, FewItemsStayInOnePartOnTheCaller) {
  const std::vector<Part> parts = parts_of(kMinItemsPerPart + 1, 4);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].end, kMinItemsPerPart + 1);
  EXPECT_EQ(parts[0].thread, std::this_thread::get_id());
  EXPECT_EQ(parts_of(0, 2).size(), 1u);  // an empty range: one empty part
}

TEST(ParallelParts, NoMorePartsThanTheItemsSupportOrThreads) {
  EXPECT_EQ(parts_of(3 * kMinItemsPerPart, 8).size(), 3u);
  EXPECT_EQ(parts_of(100 * kMinItemsPerPart, 1).size(), 1u);
  EXPECT_EQ(parts_of(100 * kMinItemsPerPart, 0).size(), 1u);  // never fewer than one
}

TEST(ParallelParts, APartsExceptionIsThrownOnTheCallerAfterEveryPartEnded) {
  std::vector<int> ended(2, 0);
  const auto work = [&](std::size_t p, std::size_t, std::size_t) {
    ended[p] = 1;
    if (p == 1) throw std::runtime_error("part 1 failed");
  };
  EXPECT_THROW(run_in_parts(4 * kMinItemsPerPart, 2, work), std::runtime_error);
  EXPECT_EQ(ended, std::vector<int>({1, 1}));
}

TEST(ParallelParts, ZeroThreadsMeansOnePerCore) {
  EXPECT_EQ(usable_threads(3), 3);
  EXPECT_GE(usable_threads(0), 1);
  EXPECT_EQ(usable_threads(0), std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
}

}  // namespace
}  // namespace odocal::batch
