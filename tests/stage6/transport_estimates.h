// Shared by the stage-6 tests: region means over several independent renders (seeds 1 ... runs)
// with the standard error from their spread, which is how a splatting or photon-mapping render,
// whose pixels are not sums of independent samples, gets an error bar.
#pragma once

#include "06-light-transport/transport_render.h"
#include "common/metrics.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <functional>
#include <span>
#include <vector>

namespace rt {

using RegionEstimate = testing::Estimate;

inline double grey(DVec3 c) { return (c.x + c.y + c.z) / 3.0; }

// `render(seed)` for seeds 1 ... runs; per region, the mean of its grey mean over the runs and the
// standard error of that mean (sample standard deviation / sqrt(runs)).
inline std::vector<RegionEstimate> region_estimates(const std::function<Image(std::uint64_t)>& render,
                                                    std::span<const PixelRect> regions, int runs) {
  std::vector<testing::SampleMean> means(regions.size());
  for (int run = 1; run <= runs; ++run) {
    const Image image = render(std::uint64_t(run));
    for (size_t r = 0; r < regions.size(); ++r) means[r].add(grey(mean_over(image, regions[r])));
  }
  std::vector<RegionEstimate> out;
  for (const testing::SampleMean& m : means) out.push_back(m.estimate());
  return out;
}

// One render of `scene` by `options`, `spp` samples (or passes) per pixel, on 2 threads.
inline Image render_method(const LightingScene& scene, const Camera& camera, const TransportOptions& options, int spp,
                           std::uint64_t seed) {
  RenderSettings settings;
  settings.width = camera.width;
  settings.height = camera.height;
  settings.spp = spp;
  settings.seed = seed;
  return testing::subject([&] {
    SampleGuard guard;
    return render_transport(scene, camera, settings, options, 2, guard).mean();
  });
}

inline TransportOptions method(TransportMethod m) {
  TransportOptions options;
  options.method = m;
  return options;
}

}  // namespace rt
