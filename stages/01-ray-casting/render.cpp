#include "01-ray-casting/render.h"

#include "common/task.h"

namespace rt {

int add_pixel_samples(const Camera& camera, const PixelFilter& filter, const RenderSettings& settings, int x, int y,
                      int begin, int end, PixelSampleSource& samples, Color& sum) {
  const std::uint64_t pixel_index = std::uint64_t(y) * std::uint64_t(camera.width) + std::uint64_t(x);
  int added = 0;
  // BEGIN TASK stage1.render.pixel_samples
  for (int k = begin; k < end && !interrupt_requested(); ++k, ++added) {
    Sampler& rng = samples.start_sample(settings.seed, pixel_index, std::uint64_t(settings.first_sample + k));
    const FilterSample s = settings.pixel_center_only ? FilterSample{Vec2(0.5f), 1.0f} : filter.sample(rng.uniform2());
    const Vec2 film_point = Vec2(float(x), float(y)) + s.film_offset;
    const Ray ray = camera.aperture_radius > 0.0f ? generate_lens_ray(camera, film_point, rng.uniform2())
                                                  : generate_camera_ray(camera, film_point);
    sum += s.weight * samples.radiance(ray);
  }
  // PLACEHOLDER
  // report_unfinished_task("stage1.render.pixel_samples");
  // if (begin == 0) {  // one ray through the pixel's centre, in the first pass only
  //   samples.start_sample(settings.seed, pixel_index, 0);
  //   sum = samples.radiance(generate_camera_ray(camera, Vec2(x + 0.5f, y + 0.5f)));
  //   added = 1;
  // }
  // (void)end, (void)filter;
  // END TASK
  return added;
}

}  // namespace rt
