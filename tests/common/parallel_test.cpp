#include "common/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
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

}  // namespace
}  // namespace rt
