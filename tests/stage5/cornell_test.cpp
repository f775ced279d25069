// Stage 5 on the Cornell box of docs/design.md against its converged reference
// (assets/references/cornell-box-256.pfm, made by the command in assets/references/README.md):
// every integrator finds the reference's mean over the box's regions, the error falls as N^-1/2,
// and ten million paths give no NaN.
#include "05-path-tracing/path_render.h"
#include "common/image_io.h"
#include "common/metrics.h"

#include "support/sample_mean.h"
#include "support/log_log_slope.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

constexpr int kSize = 64;  // tests render 64 x 64; the 256 x 256 reference is averaged down by 4

struct Cornell {
  SceneDescription description = load_scene(testing::source_path("assets/scenes/cornell-box.json"));
  LightingScene scene{description};
  Camera camera{description.camera, kSize, kSize};
  Image reference = downsample(read_pfm(testing::source_path("assets/references/cornell-box-256.pfm")), 256 / kSize);
};

const Cornell& cornell() {
  static const Cornell c;
  return c;
}

// Pixel rectangles of the 64 x 64 image, each inside one surface.
struct Region {
  const char* name;
  PixelRect rect;
};
const Region kRegions[] = {{"back wall", {36, 14, 46, 24}},
                           {"floor between the blocks", {20, 57, 30, 61}},
                           {"red wall", {4, 16, 11, 40}},
                           {"green wall", {53, 16, 60, 40}},
                           {"ceiling", {14, 2, 50, 6}}};

double grey(DVec3 c) { return (c.x + c.y + c.z) / 3.0; }

using testing::Estimate;

// The mean over a region's pixels of `spp` independent paths each (grey, the mean of R, G, B).
// The standard error comes from the spread of all the region's samples around their common mean,
// which also counts the spread between pixels, so it is conservative.
Estimate region_estimate(const Region& region, const PathOptions& options, int spp, std::uint64_t seed) {
  const Cornell& c = cornell();
  return testing::subject([&] {
    testing::SampleMean m;
    for (int y = region.rect.y0; y < region.rect.y1; ++y)
      for (int x = region.rect.x0; x < region.rect.x1; ++x)
        for (int k = 0; k < spp; ++k) {
          Rng rng(seed, std::uint64_t(y * kSize + x), std::uint64_t(k));
          const Ray ray = generate_camera_ray(c.camera, Vec2(float(x), float(y)) + rng.uniform2());
          m.add(grey(DVec3(path_radiance(c.scene, ray, options, rng))));
        }
    return m.estimate();
  });
}

TEST(CornellBox, EveryIntegratorFindsTheReferenceOnEveryRegion) {
  // 5 regions x 4 integrators, each within 3 standard errors of the reference's region mean (whose
  // own error, from 32,768 paths per 256-pixel, is far below these). The BRDF-only integrators find
  // the small light by chance, so at four times the samples they still get a looser bound.
  const Cornell& c = cornell();
  for (const Region& region : kRegions) {
    const double expected = grey(mean_over(c.reference, region.rect));
    for (const PathIntegrator integrator : kPathIntegrators) {
      PathOptions options;
      options.integrator = integrator;
      options.max_depth = 64;  // naive: 0.73^64 of the light is left out, nothing measurable
      const bool samples_lights =
          integrator == PathIntegrator::next_event_estimation || integrator == PathIntegrator::mis;
      const Estimate e = region_estimate(region, options, samples_lights ? 256 : 1024, 11);
      EXPECT_NEAR(e.mean, expected, 3.0 * e.standard_error) << region.name << ", " << integrator_name(integrator);
      EXPECT_LT(e.standard_error, (samples_lights ? 0.015 : 0.05) * expected)
          << region.name << ", " << integrator_name(integrator);
    }
  }
}

TEST(CornellBox, NaiveDepthLimitLosesTheLightOfLaterBounces) {
  // The teeth of the test above: with 2 bounces the naive integrator misses the light of the third
  // and later ones, which the regions measure as far more than 3 standard errors.
  const Cornell& c = cornell();
  PathOptions options;
  options.integrator = PathIntegrator::naive;
  options.max_depth = 2;
  const Region& ceiling = kRegions[4];
  const Estimate e = region_estimate(ceiling, options, 256, 11);
  EXPECT_LT(e.mean + 3.0 * e.standard_error, grey(mean_over(c.reference, ceiling.rect)));
}

TEST(CornellBox, ErrorFallsAsOneOverSquareRootOfSamples) {
  // RMSE against the reference over 1 to 256 spp (2.4 decades), at 32 x 32: independent samples
  // give Monte Carlo's N^-1/2 exactly (variance sigma^2 / N per pixel); a bias would flatten the
  // line at high spp. Scrambled Sobol must do at least as well, and better at 256 spp.
  // At N spp the MSE is averaged over 256 / N images of different seeds, so every level costs the
  // same and the few very bright samples of a 1-spp image do not decide the slope.
  const Cornell& c = cornell();
  const Image reference = downsample(c.reference, 2);
  const Camera camera(c.description.camera, kSize / 2, kSize / 2);
  const PathOptions options;  // MIS
  std::uint64_t dropped = 0;
  std::vector<double> spp, error[2];
  for (int n = 1; n <= 256; n *= 4) {
    spp.push_back(n);
    for (const SamplerKind sampler : {SamplerKind::independent, SamplerKind::sobol}) {
      RenderSettings settings;
      settings.width = settings.height = kSize / 2;
      settings.spp = n;
      double mse_sum = 0.0;
      const int images = 256 / n;
      for (int k = 0; k < images; ++k) {
        settings.seed = std::uint64_t(1000 + k);
        const auto [image, bad] = testing::subject([&] {
          SampleGuard guard;
          Image rendered = render_paths(c.scene, camera, settings, options, sampler, 0, guard);
          return std::pair(std::move(rendered), std::uint64_t(guard.dropped()));
        });
        mse_sum += mse(image, reference);
        dropped += bad;
      }
      error[int(sampler)].push_back(std::sqrt(mse_sum / images));
    }
  }
  const double independent = testing::log_log_slope(spp, error[0]), sobol = testing::log_log_slope(spp, error[1]);
  for (size_t i = 0; i < spp.size(); ++i) std::printf("%g spp: %.5f %.5f\n", spp[i], error[0][i], error[1][i]);
  std::printf("slopes: independent %.3f, sobol %.3f\n", independent, sobol);
  EXPECT_NEAR(independent, -0.5, 0.05);
  EXPECT_LT(sobol, -0.45);
  EXPECT_LT(error[1].back(), error[0].back());
  EXPECT_EQ(dropped, 0u);
}

TEST(CornellBox, TenMillionPathsGiveNoNanOrInfPixel) {
  // 64 x 64 x 640 paths with each of the four integrators (10.5 million), on top of the grazing and
  // corner paths of path_test.cpp: no sample is dropped and every pixel is finite.
  const Cornell& c = cornell();
  RenderSettings settings;
  settings.width = settings.height = kSize;
  settings.spp = 640;
  for (const PathIntegrator integrator : kPathIntegrators) {
    PathOptions options;
    options.integrator = integrator;
    const auto [image, dropped] = testing::subject([&] {
      SampleGuard guard;
      Image rendered = render_paths(c.scene, c.camera, settings, options, SamplerKind::sobol, 0, guard);
      return std::pair(std::move(rendered), std::uint64_t(guard.dropped()));
    });
    EXPECT_EQ(dropped, 0u) << integrator_name(integrator);
    for (const Color& pixel : image.pixels()) ASSERT_TRUE(is_finite(pixel)) << integrator_name(integrator);
  }
}

}  // namespace
}  // namespace rt
