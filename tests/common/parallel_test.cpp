#include "common/cache_line_allocator.h"
#include "common/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace rt {
namespace {

TEST(ParallelForTiles, VisitsEveryPixelExactlyOnce) {
  for (int threads : {1, 2, 7})
    for (auto [w, h] : {std::pair{1, 1}, std::pair{16, 16}, std::pair{37, 5}, std::pair{100, 65}}) {
      std::vector<std::atomic<int>> visits(size_t(w * h));
      parallel_for_tiles(w, h, threads, [&](const PixelRect& t) {
        EXPECT_LE(t.x1 - t.x0, kTileSize);
        for (int y = t.y0; y < t.y1; ++y)
          for (int x = t.x0; x < t.x1; ++x) ++visits[size_t(y * w + x)];
      });
      for (const auto& v : visits) ASSERT_EQ(v.load(), 1) << w << "x" << h << ", " << threads << " threads";
    }
}

TEST(ParallelForTiles, RethrowsTheFirstErrorAndStops) {
  std::atomic<int> tiles_run{0};
  EXPECT_THROW(parallel_for_tiles(1024, 1024, 2,
                                  [&](const PixelRect&) {
                                    ++tiles_run;
                                    throw std::runtime_error("tile failed");
                                  }),
               std::runtime_error);
  EXPECT_LT(tiles_run.load(), 64 * 64) << "remaining tiles should be skipped after a failure";
}

TEST(ParallelForTiles, ZeroThreadsMeansAllCores) {
  EXPECT_GE(resolve_thread_count(0), 1);
  EXPECT_EQ(resolve_thread_count(3), 3);
}

// Every index once, in as many chunks as threads, except where a chunk would hold under 1,024.
TEST(ForEachChunk, CoversEveryIndexOnce) {
  for (const size_t count : {0, 1, 2, 5, 1000, 2048, 5000, 100003})
    for (const int threads : {1, 2, 3, 8}) {
      std::vector<std::atomic<int>> visits(count);
      std::atomic<int> chunks{0};
      for_each_chunk(count, threads, [&](size_t begin, size_t end) {
        ++chunks;
        for (size_t i = begin; i < end; ++i) ++visits[i];
      });
      for (size_t i = 0; i < count; ++i)
        EXPECT_EQ(visits[i], 1) << count << " indices, " << threads << " threads, index " << i;
      EXPECT_EQ(chunks, std::max<size_t>(1, std::min(size_t(threads), count / 1024)))
          << count << " indices, " << threads << " threads";
    }
}

// Small arrays start on a cache line; from 2 MiB on, on a huge page's boundary. A vector that grows
// across the threshold frees each block the way it was allocated (the sanitizers check the pairing).
TEST(CacheLineAllocator, LargeArraysStartOnHugePageBoundaries) {
  struct alignas(64) TwoLines {
    std::uint8_t bytes[128];
  };
  CacheLineAllocator<TwoLines> allocator;
  const size_t huge = CacheLineAllocator<TwoLines>::kHugePage / sizeof(TwoLines);
  for (const size_t n : {size_t(1), size_t(7), huge - 1, huge, 3 * huge + 5}) {
    TwoLines* p = allocator.allocate(n);
    const auto address = reinterpret_cast<std::uintptr_t>(p);
    EXPECT_EQ(address % (n >= huge ? CacheLineAllocator<TwoLines>::kHugePage : 64), 0u) << n << " elements";
    p[n - 1] = TwoLines{};  // the whole block is usable
    allocator.deallocate(p, n);
  }
  std::vector<TwoLines, CacheLineAllocator<TwoLines>> lines;
  for (size_t i = 0; i < 2 * huge; ++i) lines.push_back(TwoLines{});
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(lines.data()) % CacheLineAllocator<TwoLines>::kHugePage, 0u);
}

}  // namespace
}  // namespace rt
