// Stage 1: the pixel loop every later stage reuses. For each pixel, `spp` samples spread uniformly
// over the pixel's area (a box filter), each one a camera ray, averaged:
//   I(x, y) = 1/N sum_k L(ray through (x + u_k, y + v_k)),   (u_k, v_k) uniform in [0, 1)^2.
// Every sample draws its numbers from Rng(seed, pixel, k), so the image does not depend on the
// thread count or the order in which tiles finish.
#pragma once

#include "01-ray-casting/camera_rays.h"
#include "common/image.h"
#include "common/parallel.h"
#include "common/progress.h"
#include "common/random.h"
#include "common/scene.h"
#include "common/task.h"

namespace rt {

// `radiance(ray, rng)` returns the radiance arriving along the camera ray, drawing any further
// random numbers it needs from `rng` (the stream after the pixel offset's two numbers).
// `progress`, if given, is advanced by the samples of each finished tile.
// `SamplerType` makes each sample's numbers from (seed, pixel, sample index): Rng (independent
// random numbers) unless a later stage passes another.
template <class SamplerType = Rng, class RadianceFn>
Image render_image(const PinholeCamera& camera, const RenderSettings& settings, int threads,
                   RadianceFn&& radiance, ProgressBar* progress = nullptr) {
  Image image(camera.width, camera.height);
  parallel_for_tiles(camera.width, camera.height, threads, [&](const Tile& tile) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const std::uint64_t pixel_index = std::uint64_t(y) * std::uint64_t(camera.width) + std::uint64_t(x);
        // BEGIN TASK stage1.render.pixel_samples
        Color sum(0.0f);
        for (int k = 0; k < settings.spp; ++k) {
          SamplerType rng(settings.seed, pixel_index, std::uint64_t(k));
          const Vec2 offset = settings.pixel_center_only ? Vec2(0.5f) : rng.uniform2();
          const Ray ray = generate_camera_ray(camera, Vec2(float(x), float(y)) + offset);
          sum += radiance(ray, rng);
        }
        image.at(x, y) = sum / float(settings.spp);
        // PLACEHOLDER
        // report_unfinished_task("stage1.render.pixel_samples");
        // Rng rng(settings.seed, pixel_index, 0);
        // image.at(x, y) = radiance(generate_camera_ray(camera, Vec2(x + 0.5f, y + 0.5f)), rng);
        // END TASK
      }
    if (progress)
      progress->advance(std::uint64_t(tile.x1 - tile.x0) * std::uint64_t(tile.y1 - tile.y0) *
                        std::uint64_t(settings.spp));
  });
  return image;
}

}  // namespace rt
