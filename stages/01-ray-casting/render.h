// Stage 1: the pixel loop every later stage reuses. For each pixel, `spp` samples spread uniformly
// over the pixel's area (a box filter), each one a camera ray, averaged:
//   I(x, y) = 1/N sum_k L(ray through (x + u_k, y + v_k)),   (u_k, v_k) uniform in [0, 1)^2.
// Every sample draws its numbers from Rng(seed, pixel, k), so the image does not depend on the
// thread count or the order in which tiles finish.
#pragma once

#include "01-ray-casting/camera_rays.h"
#include "common/image.h"
#include "common/interrupt.h"
#include "common/parallel.h"
#include "common/progress.h"
#include "common/random.h"
#include "common/scene.h"
#include "common/task.h"

namespace rt {

// `radiance(ray, rng)` returns the radiance arriving along the camera ray, drawing any further
// random numbers it needs from `rng` (the stream after the pixel offset's two numbers).
// `progress`, if given, is advanced by the samples of each finished tile (fewer than asked for
// after a stop request, which is how the program knows how much of the image it has).
// `SamplerType` makes each sample's numbers from (seed, pixel, sample index): Rng (independent
// random numbers) unless a later stage passes another.
template <class SamplerType = Rng, class RadianceFn>
Image render_image(const PinholeCamera& camera, const RenderSettings& settings, int threads,
                   RadianceFn&& radiance, ProgressBar* progress = nullptr) {
  Image image(camera.width, camera.height);
  parallel_for_tiles(camera.width, camera.height, threads, [&](const Tile& tile) {
    std::uint64_t tile_samples = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        // After Ctrl-C (common/interrupt.h) the pixels not yet started stay black.
        if (interrupt_requested()) continue;
        const std::uint64_t pixel_index = std::uint64_t(y) * std::uint64_t(camera.width) + std::uint64_t(x);
        int finished = 0;  // samples this pixel completed
        // BEGIN TASK stage1.render.pixel_samples
        // A stop request ends the loop between two samples; the pixel is then the mean of the
        // samples it has, so a stopped render is a correct, noisier image.
        Color sum(0.0f);
        for (; finished < settings.spp && !interrupt_requested(); ++finished) {
          SamplerType rng(settings.seed, pixel_index, std::uint64_t(finished));
          const Vec2 offset = settings.pixel_center_only ? Vec2(0.5f) : rng.uniform2();
          const Ray ray = generate_camera_ray(camera, Vec2(float(x), float(y)) + offset);
          sum += radiance(ray, rng);
        }
        if (finished > 0) image.at(x, y) = sum / float(finished);
        // PLACEHOLDER
        // report_unfinished_task("stage1.render.pixel_samples");
        // Rng rng(settings.seed, pixel_index, 0);
        // image.at(x, y) = radiance(generate_camera_ray(camera, Vec2(x + 0.5f, y + 0.5f)), rng);
        // finished = 1;
        // END TASK
        tile_samples += std::uint64_t(finished);
      }
    if (progress) progress->advance(tile_samples);
  });
  return image;
}

}  // namespace rt
