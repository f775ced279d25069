// Each BDPT strategy alone, unweighted, is an unbiased estimator of the paths of its length: for
// lengths 1 to 3 (edges) on the Cornell box, every (s, t) image of length k = s + t - 1 agrees,
// region by region, with path tracing's image of exactly k edges.
#include "05-path-tracing/path_tracer.h"

#include "stage6/loaded_scene.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

constexpr int kFilm = 16;  // the film's side in pixels
const PixelRect kQuadrants[] = {{0, 0, 8, 8}, {8, 0, 16, 8}, {0, 8, 8, 16}, {8, 8, 16, 16}};

// Per quadrant, the mean and standard error of `spp` independent samples per pixel, sample(x, y,
// i) giving sample i of pixel (x, y). Over the region's pixels: the mean of their means, whose
// spread includes the spread between pixels, so the error is conservative.
template <class SampleFn>
std::vector<RegionEstimate> quadrant_estimates(int spp, SampleFn&& sample) {
  return testing::subject([&] {
    std::vector<RegionEstimate> out;
    for (const PixelRect& region : kQuadrants) {
      testing::SampleMean m;
      for (int y = region.y0; y < region.y1; ++y)
        for (int x = region.x0; x < region.x1; ++x)
          for (int i = 0; i < spp; ++i) m.add(sample(x, y, i));
      out.push_back(m.estimate());
    }
    return out;
  });
}

// Path tracing's image of the paths of exactly k edges: stage 5's naive path tracer (BRDF
// sampling, no roulette) run to k - 1 bounces, minus the same path run to k - 2. The same numbers
// make the same path, so their difference is the path's k-edge term alone.
std::vector<RegionEstimate> path_traced_length(const testing::LoadedScene& c, int k, int spp) {
  PathOptions longer, shorter;
  longer.integrator = shorter.integrator = PathIntegrator::naive;
  longer.max_depth = k - 1;
  shorter.max_depth = k - 2;
  return quadrant_estimates(spp, [&](int x, int y, int i) {
    const std::uint64_t pixel = std::uint64_t(y * kFilm + x);
    Rng a(9, pixel, std::uint64_t(i)), b(9, pixel, std::uint64_t(i));
    const Vec2 film = Vec2(float(x), float(y)) + a.uniform2();
    b.uniform2();
    const Ray ray = generate_camera_ray(c.camera, film);
    double v = grey(DVec3(path_radiance(c.scene, ray, longer, a)));
    if (k >= 2) v -= grey(DVec3(path_radiance(c.scene, ray, shorter, b)));
    return v;
  });
}

void expect_strategies_of_length(int k, int pt_spp, int spp, int runs,
                                 const testing::LoadedScene& c = testing::cornell_box<kFilm, kFilm>()) {
  const std::vector<RegionEstimate> expected = path_traced_length(c, k, pt_spp);
  double lit = 0.0;
  for (const RegionEstimate& e : expected) lit += e.mean;
  ASSERT_GT(lit, 0.0) << "paths of " << k << " edges carry light";
  for (int s = 0; s <= k; ++s) {
    const int t = k + 1 - s;
    TransportOptions options = method(TransportMethod::bdpt);
    options.bdpt.only = StrategyFilter{s, t};
    const std::vector<RegionEstimate> found = region_estimates(
        [&](std::uint64_t seed) { return render_method(c.scene, c.camera, options, spp, seed); }, kQuadrants, runs);
    for (size_t r = 0; r < std::size(kQuadrants); ++r) {
      const double error = std::hypot(found[r].standard_error, expected[r].standard_error);
      EXPECT_NEAR(found[r].mean, expected[r].mean, 3.0 * error + 1e-6)
          << "strategy (" << s << ", " << t << "), length " << k << ", quadrant " << r;
    }
  }
}

TEST(BdptStrategies, EachAloneFindsThePathsOfLengthOne) { expect_strategies_of_length(1, 1024, 256, 8); }
TEST(BdptStrategies, EachAloneFindsThePathsOfLengthTwo) { expect_strategies_of_length(2, 1024, 64, 8); }
TEST(BdptStrategies, EachAloneFindsThePathsOfLengthThree) { expect_strategies_of_length(3, 1024, 64, 8); }
// On glossy walls the value of a connection depends on where the camera path came from: a
// connection that evaluated z's BSDF towards z itself (an index off by one) passed every test on
// the Lambertian box, whose BSDF ignores that direction.
TEST(BdptStrategies, EachAloneFindsThePathsOfLengthTwoOnGlossyWalls) {
  expect_strategies_of_length(2, 1024, 64, 8, testing::glossy_cornell_box<kFilm, kFilm>());
}

TEST(BdptStrategies, AllTogetherWeightedEqualTheirSum) {
  // MIS keeps the expectation: the weighted render of every strategy agrees with path tracing's
  // image of every length (stage 5's MIS integrator), on the quadrants.
  const testing::LoadedScene& c = testing::cornell_box<kFilm, kFilm>();
  const PathOptions mis;
  const std::vector<RegionEstimate> expected = quadrant_estimates(1024, [&](int x, int y, int i) {
    Rng rng(10, std::uint64_t(y * kFilm + x), std::uint64_t(i));
    const Ray ray = generate_camera_ray(c.camera, Vec2(float(x), float(y)) + rng.uniform2());
    return grey(DVec3(path_radiance(c.scene, ray, mis, rng)));
  });
  const std::vector<RegionEstimate> found = region_estimates(
      [&](std::uint64_t seed) { return render_method(c.scene, c.camera, method(TransportMethod::bdpt), 64, seed); },
      kQuadrants, 8);
  for (size_t r = 0; r < std::size(kQuadrants); ++r) {
    EXPECT_GT(expected[r].mean, 0.05) << "quadrant " << r << ": the path tracer sees the lit box";
    EXPECT_NEAR(found[r].mean, expected[r].mean, 3.0 * std::hypot(found[r].standard_error, expected[r].standard_error))
        << "quadrant " << r;
  }
}

}  // namespace
}  // namespace rt
