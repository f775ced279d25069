// Stage 5: adaptive sampling. The stopping test at its boundaries; the loop's promises (each pixel
// between the minimum and the maximum, only noisy pixels going on, the same sums as the uniform
// render where a pixel never stops, the same result for any thread count). The program's flags,
// heat map and refusals are tested with its other flags (cli_test.cpp, Stage5Adaptive).
#include "05-path-tracing/adaptive_sampling.h"
#include "05-path-tracing/path_render.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

PixelStatistics of(std::initializer_list<double> values) {
  PixelStatistics s;
  for (const double v : values) s.add(v);
  return s;
}

TEST(PixelConverged, HalfWidthAgainstTheToleranceAtTheBoundary) {
  // {1, 3}: mean 2, unbiased variance ((1 - 2)^2 + (3 - 2)^2) / (2 - 1) = 2, so I = 1.96 sqrt(2 / 2)
  // = 1.96, and the test passes exactly from tolerance 1.96 / 2 = 0.98 on (<=, not <).
  const PixelStatistics two = of({1.0, 3.0});
  EXPECT_TRUE(RT_GRADED(pixel_converged)(two, 0.98f));
  EXPECT_FALSE(RT_GRADED(pixel_converged)(two, 0.979f));
  // With the biased variance (divided by n = 2) I would be 1.386 and 0.7 would pass.
  EXPECT_FALSE(RT_GRADED(pixel_converged)(two, 0.7f));
  // Four samples {1, 3, 1, 3}: variance 4/3, I = 1.96 sqrt(4 / 3 / 4) = 1.1316, boundary 0.5658.
  const PixelStatistics four = of({1.0, 3.0, 1.0, 3.0});
  EXPECT_TRUE(RT_GRADED(pixel_converged)(four, 0.566f));
  EXPECT_FALSE(RT_GRADED(pixel_converged)(four, 0.565f));
}

TEST(PixelConverged, NeedsTwoSamplesAndTakesAFlatPixelAtOnce) {
  EXPECT_FALSE(RT_GRADED(pixel_converged)(of({}), 1.0f));
  EXPECT_FALSE(RT_GRADED(pixel_converged)(of({5.0}), 1.0f)) << "one sample says nothing of the spread";
  EXPECT_TRUE(RT_GRADED(pixel_converged)(of({0.5, 0.5, 0.5}), 1e-6f)) << "no spread: done";
  EXPECT_TRUE(RT_GRADED(pixel_converged)(of({0.0, 0.0}), 1e-6f)) << "black and certain: done";
  EXPECT_FALSE(RT_GRADED(pixel_converged)(of({0.0, 2.0, 0.0, 0.0}), 0.5f));
}

// A scene of hard and easy pixels: a glossy floor under a sky with a bright patch, and plain sky.
SceneDescription patchy_scene() {
  SceneDescription d;
  d.source = "adaptive";
  Material floor;
  floor.type = MaterialType::phong;
  floor.albedo = Color(0.3f);
  floor.specular = Color(0.5f);
  floor.shininess = 50.0f;
  d.materials.push_back(floor);
  d.shapes.push_back(Shape{"floor", Quad{{Vec3(-10, 0, -10), Vec3(-10, 0, 10), Vec3(10, 0, 10), Vec3(10, 0, -10)}}, 0});
  auto sky = std::make_shared<Image>(16, 8, Color(0.5f, 0.6f, 0.9f));
  sky->at(3, 1) = Color(200.0f);
  d.environment = Environment{};
  d.environment->image = sky;
  d.camera.position = Vec3(0, 2, 6);
  d.camera.look_at = Vec3(0, 1, 0);
  return d;
}


SampleSums render(const LightingScene& scene, const SceneDescription& d, const RenderSettings& settings, int threads,
                  const AdaptiveSettings* adaptive) {
  const Camera camera(d.camera, settings.width, settings.height);
  SampleGuard guard;
  return testing::subject([&] {
    return render_path_samples(scene, camera, settings, PathOptions{}, SamplerKind::independent, threads, guard,
                               nullptr, adaptive);
  });
}

class AdaptiveRender : public ::testing::Test {
 protected:
  SceneDescription description = patchy_scene();
  LightingScene scene{description};
  RenderSettings settings = [] {
    RenderSettings s;
    s.width = 24;
    s.height = 16;
    s.spp = 256;
    return s;
  }();
};

TEST_F(AdaptiveRender, SkyStopsAtTheMinimumNoisyFloorGoesOn) {
  AdaptiveSettings adaptive;
  adaptive.tolerance = 0.05f;
  adaptive.min_spp = 16;
  const SampleSums sums = render(scene, description, settings, 2, &adaptive);
  // The top rows see the sky's even part: no spread, done at the first test.
  for (int x = 0; x < settings.width; ++x) EXPECT_EQ(sums.count(x, 0), 16u) << x;
  std::uint32_t most = 0;
  for (const std::uint32_t n : sums.counts()) {
    EXPECT_GE(n, 16u);
    EXPECT_LE(n, 256u);
    EXPECT_EQ(n % 16u, 0u) << "tests come every batch of 16";
    most = std::max(most, n);
  }
  EXPECT_EQ(most, 256u) << "some floor pixel needs every path it may take";
}

TEST_F(AdaptiveRender, NeverConvergingIsTheUniformRenderBitForBit) {
  AdaptiveSettings never;
  never.tolerance = 1e-6f;  // only pixels with no spread at all stop
  const SampleSums adaptive = render(scene, description, settings, 2, &never);
  const SampleSums uniform = render(scene, description, settings, 2, nullptr);
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      if (adaptive.count(x, y) != 256u) continue;  // the flat sky stopped early
      EXPECT_EQ(adaptive.sum(x, y), uniform.sum(x, y)) << x << ", " << y;
    }
  EXPECT_EQ(adaptive.count(12, 15), 256u) << "a floor pixel";
}

TEST_F(AdaptiveRender, SameSumsAndCountsForAnyThreadCount) {
  AdaptiveSettings adaptive;
  adaptive.tolerance = 0.1f;
  const SampleSums one = render(scene, description, settings, 1, &adaptive);
  const SampleSums two = render(scene, description, settings, 2, &adaptive);
  EXPECT_TRUE(one.sums() == two.sums());
  EXPECT_TRUE(one.counts() == two.counts());
}

TEST_F(AdaptiveRender, ReachesTheUniformErrorWithFewerPaths) {
  // Against a 4096-path reference, adaptive sampling at 5 % spends fewer paths than the uniform
  // render at its maximum, for an error no worse than twice the uniform one's.
  RenderSettings reference_settings = settings;
  reference_settings.spp = 4096;
  reference_settings.seed = 99;
  const Image reference = render(scene, description, reference_settings, 2, nullptr).mean();
  AdaptiveSettings adaptive;
  adaptive.tolerance = 0.05f;
  const SampleSums a = render(scene, description, settings, 2, &adaptive);
  const SampleSums u = render(scene, description, settings, 2, nullptr);
  auto error = [&](const Image& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixel_count(); ++i) {
      const Vec3 d = image.pixels()[i] - reference.pixels()[i];
      sum += double(glm::dot(d, d));
    }
    return sum / double(image.pixel_count());
  };
  EXPECT_LT(a.total_count(), u.total_count() * 9 / 10);
  EXPECT_LT(error(a.mean()), 2.0 * error(u.mean())) << "adaptive " << error(a.mean()) << ", uniform " << error(u.mean());
}

}  // namespace
}  // namespace rt
