// The pixel loop every renderer shares: passes over the image, each pass a few samples of every
// pixel, so that a render stopped by Ctrl-C is a whole image with (almost) the same number of
// samples in every pixel, not a few finished pixels. Each method brings its work for one pixel of
// one pass; the passes, the tiles on the worker threads, the stop checks and the progress bar are
// here.
#pragma once

#include "common/image.h"
#include "common/interrupt.h"
#include "common/parallel.h"
#include "common/progress.h"

#include <algorithm>
#include <cstdint>

namespace rt {

// Samples [begin, end) of each pixel: one pass.
struct PixelPass {
  int begin = 0, end = 0;
  friend bool operator==(const PixelPass&, const PixelPass&) = default;
};

// Runs passes of `per_pass` samples of each pixel of a width x height image until `spp` samples, or
// until a stop is requested (checked before each pass and each tile). In a pass, the tiles run on
// `threads` threads (parallel_for_tiles), and each calls pixel(tile, x, y, pass) for its pixels,
// row by row, which returns the samples it added; the progress bar, if any, advances by each
// tile's total. Then after_pass(pass) runs on the calling thread, also for a pass that a stop cut
// short (it may check interrupt_requested() to drop that pass). A pixel's samples are the same
// whichever thread takes its tile, so a method that keeps each pixel's samples in order renders the
// same image bit for bit for any thread count.
template <class PixelFn, class AfterPassFn>
void render_in_passes(int width, int height, int spp, int per_pass, int threads, ProgressBar* progress, PixelFn&& pixel,
                      AfterPassFn&& after_pass) {
  per_pass = std::max(per_pass, 1);
  for (int begin = 0; begin < spp && !interrupt_requested(); begin += per_pass) {
    const PixelPass pass{begin, std::min(spp, begin + per_pass)};
    parallel_for_tiles(width, height, threads, [&](const PixelRect& tile) {
      if (interrupt_requested()) return;
      std::uint64_t tile_samples = 0;
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) tile_samples += std::uint64_t(pixel(tile, x, y, pass));
      if (progress) progress->advance(tile_samples);
    });
    after_pass(pass);
  }
}

// The same with nothing to do between passes.
template <class PixelFn>
void render_in_passes(int width, int height, int spp, int per_pass, int threads, ProgressBar* progress,
                      PixelFn&& pixel) {
  render_in_passes(width, height, spp, per_pass, threads, progress, pixel, [](const PixelPass&) {});
}

}  // namespace rt
