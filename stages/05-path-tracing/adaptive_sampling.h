// Stage 5: adaptive sampling. A pixel of flat sky is done after a few paths; a pixel of a glossy
// caustic needs thousands. Instead of the same N everywhere, each pixel takes samples in batches
// and stops once its estimate is known well enough: after every batch, with n samples x_k of the
// pixel's luminance so far (mean mu, sample standard deviation sigma), the 95 % confidence
// interval of the mean has half-width
//     I = 1.96 sigma / sqrt(n),
// and the pixel is done when I <= tolerance x mu: its relative error is then below the tolerance
// with 95 % confidence (the test of Berkeley CS184's path tracer, "adaptive sampling"). A minimum
// number of samples guards against a pixel that happened to see the same value a few times, a
// maximum (the render's spp) bounds the time.
//
// The stopping rule makes the estimator slightly biased (whether a pixel stops depends on the
// values it has seen), which is why the tests compare it with the uniform render by error, not
// by expectation. Every pixel decides from its own samples only, and each sample's numbers still
// come from (seed, pixel, sample index): the image and the sample counts are the same bit for bit
// for any thread count. Batches rendered apart (--sample-range) cannot be merged into it, since
// no run knows where another would have stopped: the programs refuse that combination.
#pragma once

#include "01-ray-casting/render.h"
#include "common/display_transform.h"

#include <cstdint>
#include <vector>

namespace rt {

struct AdaptiveSettings {
  float tolerance = 0.05f;  // the largest relative half-width of the 95 % interval
  int min_spp = 16;         // samples before the first test
  int batch = 16;           // samples between two tests
};

// A pixel's running sums of its samples' luminance, in double: the variance is formed from the
// difference of two sums, which float would cancel away.
struct PixelStatistics {
  double sum = 0.0, sum_of_squares = 0.0;
  std::uint32_t count = 0;

  void add(double x) {
    sum += x;
    sum_of_squares += x * x;
    ++count;
  }
};

// Task stage5.adaptive.converged. Whether I = 1.96 sigma / sqrt(n) <= tolerance x mu, with
// sigma^2 = (sum x^2 - n mu^2) / (n - 1), the unbiased sample variance; never with fewer than two
// samples (no spread is known from one).
bool pixel_converged(const PixelStatistics& statistics, float tolerance);

// Stage 1's pixel loop, adaptively: every pixel of the window takes batches of samples
// (add_pixel_samples, one sample at a time so that each sample's luminance is seen) until it has
// `settings.spp` or passes pixel_converged after at least min_spp. The sums and counts come back
// as from render_samples; a pixel that never converges has exactly the uniform render's sum.
template <SamplerType S = Rng, class RadianceFn>
SampleSums render_adaptive(const Camera& camera, const RenderSettings& settings, const AdaptiveSettings& adaptive,
                           int threads, RadianceFn&& radiance, ProgressBar* progress = nullptr) {
  const PixelRect window = settings.window();
  const PixelFilter filter(settings.filter);
  SampleSums sums(window.width(), window.height());
  std::vector<PixelStatistics> statistics(window.area());
  std::vector<std::uint8_t> done(window.area(), 0);
  render_in_passes(
      window.width(), window.height(), settings.spp, adaptive.batch, threads, progress,
      [&](const PixelRect&, int x, int y, const PixelPass& pass) {
        const size_t i = size_t(y) * size_t(window.width()) + size_t(x);
        if (done[i]) return 0;
        Color sum = sums.sum(x, y);
        int added = 0;
        for (int k = pass.begin; k < pass.end; ++k) {
          Color sample(0.0f);
          if (add_pixel_samples<S>(camera, filter, settings, window.x0 + x, window.y0 + y, k, k + 1, radiance,
                                   sample) == 0)
            break;  // a stop request
          sum += sample;
          statistics[i].add(double(luminance(sample)));
          ++added;
        }
        sums.set(x, y, sum, sums.count(x, y) + std::uint32_t(added));
        if (int(statistics[i].count) >= adaptive.min_spp && pixel_converged(statistics[i], adaptive.tolerance))
          done[i] = 1;
        return added;
      });
  return sums;
}

}  // namespace rt
