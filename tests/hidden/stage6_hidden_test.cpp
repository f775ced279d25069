// Hidden tests of stage 6: the furnace at an albedo and emission no visible test uses, by light
// tracing and BDPT; the progressive update and the MIS weight at random inputs; the pinhole's
// projection for another camera.
#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "common/random.h"
#include "stage5/path_estimates.h"
#include "stage6/records.h"
#include "stage6/transport_estimates.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

TEST(HiddenTransportFurnace, LightTracingAndBdptFindTheClosedForm) {
  const LightingScene scene = furnace(0.3f, 1.4f, 1.5f);  // L = Le / (1 - rho) = 2
  CameraSpec spec;
  spec.position = Vec3(0.2f, -0.1f, 0.0f);
  spec.look_at = Vec3(0.5f, 0.2f, 1.0f);
  const Camera camera(spec, 12, 12);
  const PixelRect all[] = {{0, 0, 12, 12}};
  for (const TransportMethod m : {TransportMethod::lt, TransportMethod::bdpt}) {
    // Light tracing lands only the share of its paths that the small film sees: more of them.
    const int spp = m == TransportMethod::lt ? 256 : 16;
    const std::vector<RegionEstimate> e = region_estimates(
        [&](std::uint64_t seed) { return render_method(scene, camera, method(m), spp, seed + 40); }, all, 8);
    EXPECT_NEAR(e[0].mean, 2.0, 4.0 * e[0].standard_error + 1e-4) << method_name(m);
    EXPECT_LT(e[0].standard_error, 0.03) << method_name(m);  // tight enough to mean something
  }
}

TEST(HiddenStage6Formulas, ProgressiveUpdateAtRandomInputs) {
  Rng rng(6161, 0, 0);
  for (int i = 0; i < 300; ++i) {
    const double n = 50.0 * rng.uniform();
    const float r = 0.1f + rng.uniform(), alpha = 0.2f + 0.8f * rng.uniform();
    const int m = int(40.0f * rng.uniform()) + 1;
    PhotonStatistics s{n, r, Color(rng.uniform())};
    const Color flux(rng.uniform());
    const Color tau = s.tau;
    s = testing::subject([&] {
      PhotonStatistics updated = s;
      progressive_update(updated, m, flux, alpha);
      return updated;
    });
    const double kept = n + alpha * m, shrink = kept / (n + m);
    EXPECT_NEAR(s.photons, kept, 1e-4);
    EXPECT_NEAR(s.radius, r * std::sqrt(shrink), 1e-5);
    EXPECT_NEAR(s.tau.x, (tau.x + flux.x) * shrink, 1e-5);
  }
}

TEST(HiddenStage6Formulas, StrategyWeightsOfRandomDensitiesSumToOne) {
  // A path of k + 1 vertices with made-up densities from either side; split every way.
  Rng rng(6262, 0, 0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + int(5.0f * rng.uniform());
    std::vector<float> from_camera(size_t(n), 1.0f), from_light(size_t(n), 1.0f);
    for (int i = 0; i < n; ++i) {
      from_camera[size_t(i)] = 0.01f + 3.0f * rng.uniform();
      from_light[size_t(i)] = 0.01f + 3.0f * rng.uniform();
    }
    double sum = 0.0;
    for (int s = 0; s < n; ++s) {
      const int t = n - s;
      std::vector<VertexDensity> camera, light;
      for (int i = 0; i < t; ++i) camera.push_back({from_camera[size_t(i)], from_light[size_t(i)], false});
      for (int j = 0; j < s; ++j) light.push_back({from_light[size_t(n - 1 - j)], from_camera[size_t(n - 1 - j)], false});
      sum += RT_GRADED(strategy_weight)(camera, light);
    }
    EXPECT_NEAR(sum, 1.0, 1e-5) << "trial " << trial;
  }
}

TEST(HiddenProjection, AnotherCamera) {
  CameraSpec spec;
  spec.position = Vec3(-3.0f, 0.5f, 2.0f);
  spec.look_at = Vec3(1.0f, -1.0f, 0.0f);
  spec.up = Vec3(0.1f, 1.0f, 0.0f);
  spec.vfov_degrees = 75.0f;
  const Camera camera(spec, 90, 160);
  Rng rng(6363, 0, 0);
  for (int k = 0; k < 200; ++k) {
    const Vec2 film(rng.uniform() * 90.0f, rng.uniform() * 160.0f);
    const std::optional<Vec2> back =
        RT_GRADED(project_to_film)(camera, RT_GRADED(generate_camera_ray)(camera, film).at(3.0f));
    ASSERT_TRUE(back);
    EXPECT_NEAR(back->x, film.x, 2e-3f);
    EXPECT_NEAR(back->y, film.y, 2e-3f);
  }
}

}  // namespace
}  // namespace rt
