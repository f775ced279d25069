// Stage 1: the pixel loop every later stage reuses. For each pixel, `spp` samples spread over and
// around the pixel by its reconstruction filter (pixel_filter.h; the box: uniformly over the pixel's
// area), each one a camera ray (through a lens point too, when the camera has an aperture),
// weighted and averaged:
//   I(x, y) = 1/N sum_k w_k L(ray through (x, y) + offset_k),
// offset_k and w_k the filter's sample for (u_k, v_k) uniform in [0, 1)^2 (w = 1 for the box).
// Every sample draws its numbers from Rng(seed, pixel, k), so the image does not depend on the
// thread count or the order in which tiles finish, and samples [a, b) rendered in one run are
// exactly samples [a, b) of any other run: batches rendered apart add up (docs/scale-out.md).
#pragma once

#include "01-ray-casting/camera_rays.h"
#include "01-ray-casting/pixel_filter.h"
#include "common/image.h"
#include "common/pixel_passes.h"
#include "common/program.h"
#include "common/progress.h"
#include "common/random.h"
#include "common/sample_sums.h"
#include "common/scene.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <type_traits>

namespace rt {

// Where a pixel's samples take their numbers and their radiance: start_sample gives sample
// `sample_index`'s sampler, made from (seed, pixel index, sample index), and radiance(ray) the
// radiance arriving along a ray, drawing any further numbers from that same sampler. An interface,
// so that the task below is an ordinary function whatever sampler and integrator a stage brings
// (two virtual calls a sample, against a ray's worth of work).
class PixelSampleSource {
 public:
  virtual Sampler& start_sample(std::uint64_t seed, std::uint64_t pixel_index, std::uint64_t sample_index) = 0;
  virtual Color radiance(const Ray& ray) = 0;

 protected:
  ~PixelSampleSource() = default;
};

// Task stage1.render.pixel_samples: adds samples [begin, end) of pixel (x, y) to `sum` and returns
// how many it added. Sample k is the camera ray through (x, y) + the film offset of `filter`'s
// sample (settings.filter's) for (u, v), the first two numbers of sample first_sample + k's
// sampler (samples.start_sample with settings.seed and the pixel's index y * width + x), or
// through the pixel's centre for settings.pixel_center_only; its radiance (samples.radiance) times
// the sample's weight is added. A camera with an aperture takes its lens point from the next two
// numbers (generate_lens_ray); a pinhole draws none, so pinhole renders are what they always were.
// The same numbers whichever run, thread or pass takes the sample. A stop request
// (common/interrupt.h) ends the loop between two samples: the pixel keeps the samples it finished.
int add_pixel_samples(const Camera& camera, const PixelFilter& filter, const RenderSettings& settings, int x, int y,
                      int begin, int end, PixelSampleSource& samples, Color& sum);

// The source of samplers of type S (Rng unless a later stage passes another) and a radiance function
// `radiance(ray, sampler)`.
template <SamplerType S, class RadianceFn>
class PixelSamplesOf final : public PixelSampleSource {
 public:
  explicit PixelSamplesOf(RadianceFn& radiance) : radiance_(radiance) {}
  Sampler& start_sample(std::uint64_t seed, std::uint64_t pixel_index, std::uint64_t sample_index) override {
    return sampler_.emplace(seed, pixel_index, sample_index);
  }
  Color radiance(const Ray& ray) override { return radiance_(ray, *sampler_); }

 private:
  RadianceFn& radiance_;
  std::optional<S> sampler_;
};

// add_pixel_samples with the samples of S and `radiance(ray, sampler)`.
template <SamplerType S, class RadianceFn>
int add_pixel_samples(const Camera& camera, const PixelFilter& filter, const RenderSettings& settings, int x, int y,
                      int begin, int end, RadianceFn&& radiance, Color& sum) {
  PixelSamplesOf<S, std::remove_reference_t<RadianceFn>> samples(radiance);
  return add_pixel_samples(camera, filter, settings, x, y, begin, end, samples, sum);
}

// Samples per pass over the image (render_samples): enough that a pass holds at least 2^16
// samples, so the per-pass start of the worker threads (some 50 us) stays under 1% of a pass for
// any stage; one sample per pixel from 256 x 256 pixels up.
inline int samples_per_pass(std::int64_t pixels, int spp) {
  constexpr std::int64_t kSamplesPerPass = std::int64_t(1) << 16;
  return int(std::clamp<std::int64_t>((kSamplesPerPass + pixels - 1) / std::max<std::int64_t>(pixels, 1), 1, spp));
}

// Renders samples [first_sample, first_sample + spp) of each pixel of `settings.window()` and
// returns, per pixel of that window, their sum and number (the window's pixel (0, 0) is the
// image's (x0, y0)). The samples are taken in passes over the whole window (render_in_passes),
// samples_per_pass of each pixel a pass. Each pixel adds its samples in the order k = 0, 1, 2, ...
// whichever thread takes its tile in each pass, so the image is the same bit for bit for any thread
// count and any pass size. `progress`, if given, is advanced by the samples each tile finishes
// (fewer than asked for after a stop request, which is how the program knows how much it has).
// `S` makes each sample's numbers from (seed, pixel, sample index): Rng (independent random
// numbers) unless a later stage passes another.
template <SamplerType S = Rng, class RadianceFn>
SampleSums render_samples(const Camera& camera, const RenderSettings& settings, int threads, RadianceFn&& radiance,
                          ProgressBar* progress = nullptr) {
  const PixelRect window = settings.window();
  const PixelFilter filter(settings.filter);  // once: it tabulates its inverse distribution
  SampleSums sums(window.width(), window.height());
  render_in_passes(window.width(), window.height(), settings.spp, samples_per_pass(window.area(), settings.spp),
                   threads, progress, [&](const PixelRect&, int x, int y, const PixelPass& pass) {
                     Color sum = sums.sum(x, y);
                     const int added = add_pixel_samples<S>(camera, filter, settings, window.x0 + x, window.y0 + y,
                                                            pass.begin, pass.end, radiance, sum);
                     sums.set(x, y, sum, sums.count(x, y) + std::uint32_t(added));
                     return added;
                   });
  return sums;
}

// A stage program's whole run: stage 1's pixel loop over `camera` with `radiance`, behind the
// program shell's progress bar and output (common/program.h).
template <SamplerType S = Rng, class RadianceFn>
void render_and_write(const char* program, const CommonOptions& options, const SceneDescription& description,
                      const RenderSettings& settings, const Camera& camera, PixelMeaning meaning,
                      RadianceFn&& radiance) {
  render_with_progress_and_write(program, options, description, settings, meaning, [&](ProgressBar* progress) {
    return render_samples<S>(camera, settings, options.threads, radiance, progress);
  });
}

// The image: each pixel the mean of its samples (SampleSums::mean).
template <SamplerType S = Rng, class RadianceFn>
Image render_image(const Camera& camera, const RenderSettings& settings, int threads, RadianceFn&& radiance,
                   ProgressBar* progress = nullptr) {
  return render_samples<S>(camera, settings, threads, std::forward<RadianceFn>(radiance), progress).mean();
}

}  // namespace rt
