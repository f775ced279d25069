#include "common/interrupt.h"
#include "common/pixel_passes.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace rt {
namespace {

// Each pixel's calls in one render: the passes it was given, in order.
struct PassLog {
  std::vector<std::vector<PixelPass>> per_pixel;
  std::vector<PixelPass> after;
};

PassLog run_passes(int width, int height, int spp, int per_pass, int threads, ProgressBar* progress = nullptr) {
  PassLog log;
  log.per_pixel.resize(size_t(width) * size_t(height));
  render_in_passes(
      width, height, spp, per_pass, threads, progress,
      [&](const PixelRect& tile, int x, int y, const PixelPass& pass) {
        EXPECT_TRUE(tile.contains(x, y));
        log.per_pixel[size_t(y) * size_t(width) + size_t(x)].push_back(pass);
        return pass.end - pass.begin;
      },
      [&](const PixelPass& pass) { log.after.push_back(pass); });
  return log;
}

TEST(PixelPasses, EveryPixelTakesEveryPassOnceAndInOrderTheLastCutAtSpp) {
  const std::vector<PixelPass> expected{{0, 3}, {3, 6}, {6, 7}};
  for (const int threads : {1, 2, 5}) {
    const PassLog log = run_passes(37, 21, 7, 3, threads);
    for (const std::vector<PixelPass>& passes : log.per_pixel) EXPECT_EQ(passes, expected);
    EXPECT_EQ(log.after, expected) << "after_pass runs once after each pass";
  }
}

TEST(PixelPasses, APassOfOneSampleAndAPassSizeBeyondSpp) {
  EXPECT_EQ(run_passes(3, 2, 2, 1, 1).per_pixel[5], (std::vector<PixelPass>{{0, 1}, {1, 2}}));
  EXPECT_EQ(run_passes(3, 2, 2, 9, 1).per_pixel[0], (std::vector<PixelPass>{{0, 2}}));
  EXPECT_EQ(run_passes(3, 2, 2, 0, 1).after.size(), 2u) << "a pass size below 1 is one sample a pass";
}

TEST(PixelPasses, TheProgressBarCountsWhatEachPixelSaysItAdded) {
  ProgressBar progress(40 * 30 * 5, "samples", false);
  run_passes(40, 30, 5, 2, 2, &progress);
  EXPECT_EQ(progress.done(), 40u * 30u * 5u);
}

TEST(PixelPasses, AStopRequestEndsTheLoopBeforeTheNextPassAndTile) {
  clear_interrupt();
  std::atomic<int> calls{0};
  std::vector<PixelPass> after;
  render_in_passes(
      64, 64, 10, 1, 1, nullptr,
      [&](const PixelRect&, int, int, const PixelPass&) {
        if (++calls == 10) request_interrupt(2);
        return 1;
      },
      [&](const PixelPass& pass) { after.push_back(pass); });
  clear_interrupt();
  // One thread: the stop comes in the first tile (16 x 16 pixels), which finishes; no later tile
  // starts, the cut pass still gets its after_pass, and no pass follows.
  EXPECT_EQ(calls.load(), kTileSize * kTileSize);
  EXPECT_EQ(after, (std::vector<PixelPass>{{0, 1}}));
}

}  // namespace
}  // namespace rt
