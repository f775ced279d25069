// Stage 1: the pixel loop every later stage reuses. For each pixel, `spp` samples spread uniformly
// over the pixel's area (a box filter), each one a camera ray, averaged:
//   I(x, y) = 1/N sum_k L(ray through (x + u_k, y + v_k)),   (u_k, v_k) uniform in [0, 1)^2.
// Every sample draws its numbers from Rng(seed, pixel, k), so the image does not depend on the
// thread count or the order in which tiles finish, and samples [a, b) rendered in one run are
// exactly samples [a, b) of any other run: batches rendered apart add up (docs/scale-out.md).
#pragma once

#include "01-ray-casting/camera_rays.h"
#include "common/image.h"
#include "common/interrupt.h"
#include "common/parallel.h"
#include "common/progress.h"
#include "common/random.h"
#include "common/sample_sums.h"
#include "common/scene.h"
#include "common/task.h"

namespace rt {

// `radiance(ray, rng)` returns the radiance arriving along the camera ray, drawing any further
// random numbers it needs from `rng` (the stream after the pixel offset's two numbers).
// Renders samples [first_sample, first_sample + spp) of each pixel of `settings.window()` and
// returns, per pixel of that window, their sum and number (the window's pixel (0, 0) is the
// image's (x0, y0)). `progress`, if given, is advanced by the samples of each finished tile (fewer
// than asked for after a stop request, which is how the program knows how much it has).
// `SamplerType` makes each sample's numbers from (seed, pixel, sample index): Rng (independent
// random numbers) unless a later stage passes another.
template <class SamplerType = Rng, class RadianceFn>
SampleSums render_samples(const PinholeCamera& camera, const RenderSettings& settings, int threads,
                          RadianceFn&& radiance, ProgressBar* progress = nullptr) {
  const PixelRect window = settings.window();
  SampleSums sums(window.width(), window.height());
  parallel_for_tiles(window.width(), window.height(), threads, [&](const Tile& tile) {
    std::uint64_t tile_samples = 0;
    for (int ty = tile.y0; ty < tile.y1; ++ty)
      for (int tx = tile.x0; tx < tile.x1; ++tx) {
        // After Ctrl-C (common/interrupt.h) the pixels not yet started keep no samples.
        if (interrupt_requested()) continue;
        const int x = window.x0 + tx, y = window.y0 + ty;  // the pixel in the whole image
        const std::uint64_t pixel_index = std::uint64_t(y) * std::uint64_t(camera.width) + std::uint64_t(x);
        Color sum(0.0f);
        int finished = 0;  // samples this pixel completed
        // BEGIN TASK stage1.render.pixel_samples
        // A stop request ends the loop between two samples; the pixel then keeps the samples it
        // has, so a stopped render is a correct, noisier image.
        for (; finished < settings.spp && !interrupt_requested(); ++finished) {
          SamplerType rng(settings.seed, pixel_index, std::uint64_t(settings.first_sample + finished));
          const Vec2 offset = settings.pixel_center_only ? Vec2(0.5f) : rng.uniform2();
          const Ray ray = generate_camera_ray(camera, Vec2(float(x), float(y)) + offset);
          sum += radiance(ray, rng);
        }
        // PLACEHOLDER
        // report_unfinished_task("stage1.render.pixel_samples");
        // Rng rng(settings.seed, pixel_index, 0);
        // sum = radiance(generate_camera_ray(camera, Vec2(x + 0.5f, y + 0.5f)), rng);
        // finished = 1;
        // END TASK
        sums.set(tx, ty, sum, std::uint32_t(finished));
        tile_samples += std::uint64_t(finished);
      }
    if (progress) progress->advance(tile_samples);
  });
  return sums;
}

// The image: each pixel the mean of its samples (SampleSums::mean).
template <class SamplerType = Rng, class RadianceFn>
Image render_image(const PinholeCamera& camera, const RenderSettings& settings, int threads,
                   RadianceFn&& radiance, ProgressBar* progress = nullptr) {
  return render_samples<SamplerType>(camera, settings, threads, std::forward<RadianceFn>(radiance), progress).mean();
}

}  // namespace rt
