// Stage 5: the path tracer against closed forms (the furnace, stage 4's direct-lighting scenes and
// Lambert's polygon formula), Russian roulette, and paths that graze and hit corners.
#include "05-path-tracing/path_render.h"
#include "04-radiometry/radiometry.h"
#include "stage4/closed_form.h"
#include "stage5/path_estimates.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

TEST(Furnace, EveryIntegratorFindsLeOverOneMinusRho) {
  // A closed Lambertian enclosure: L = Le + rho L everywhere, so L = Le / (1 - rho) = 1 here. The
  // naive integrator stops after D bounces: L_D = Le (1 - rho^(D+1)) / (1 - rho).
  const LightingScene scene = furnace(0.5f, 0.5f);
  PathOptions options;
  options.max_depth = 5;
  for (const Vec3 d : {Vec3(0, 0, 1), glm::normalize(Vec3(1, 1, 1)), glm::normalize(Vec3(0.3f, -1, 0.01f))})
    for (const PathIntegrator i : kPathIntegrators) {
      options.integrator = i;
      const Estimate e = estimate(scene, Ray{Vec3(0.1f, 0.2f, -0.3f), d}, options, 30000);
      const double exact = i == PathIntegrator::naive ? 0.5 * (1.0 - std::pow(0.5, 6)) / 0.5 : 1.0;
      EXPECT_NEAR(e.mean, exact, 4.0 * e.standard_error + 1e-5) << integrator_name(i);
      EXPECT_LT(e.standard_error, 0.02) << integrator_name(i);  // 2% of the answer, as in stage 4
    }
}

TEST(PathClosedForm, DiskOverAnOpenFloor) {
  // Stage 4's coaxial disk over a floor, with nothing for light to bounce back from: the path
  // tracer's answer is the direct light alone, rho L F.
  const std::string json = R"({"camera": {"position": [3, 0.2, 0], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"floor": {"albedo": [0.5, 0.5, 0.5]}, "light": {"emission": [4, 4, 4], "albedo": [0, 0, 0]}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-10, 0, -10], [-10, 0, 10], [10, 0, 10], [10, 0, -10]]},
               {"type": "disk", "material": "light", "center": [0, 1, 0], "normal": [0, -1, 0], "radius": 0.5}]})";
  const LightingScene scene(parse_scene(json, "disk.json"));
  const double exact = 0.5 * 4.0 * testing::factor_to_coaxial_disk(0.5, 1.0);
  PathOptions options;
  for (const PathIntegrator i : kPathIntegrators) {
    options.integrator = i;
    const Estimate e = estimate(scene, Ray{Vec3(3, 0.2f, 0), glm::normalize(Vec3(-3, -0.2f, 0))}, options, 40000);
    EXPECT_NEAR(e.mean, exact, 4.0 * e.standard_error) << integrator_name(i);
    EXPECT_LT(e.standard_error, 0.02 * exact) << integrator_name(i);
  }
}

TEST(PathClosedForm, QuadLightMatchesLambertsPolygonFormula) {
  // A trapezoid light, split into triangles of areas 1 and 2, facing down over an open floor: the floor
  // radiance is rho E / pi with E from Lambert's polygon formula (Arvo 1995), at points under the
  // small half, under the large half, and beside the light. Choosing the halves with equal
  // probability while dividing by the density of a uniform point on the whole quad would weigh the
  // small half by 3/2 and the large one by 3/4: the first point brighter, the second darker, far
  // outside the bound, where an image of the whole floor could average the two away.
  const std::string json = R"({"camera": {"position": [0, 3, -3], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"floor": {"albedo": [0.5, 0.5, 0.5]}, "light": {"emission": [3, 3, 3], "albedo": [0, 0, 0]}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-10, 0, -10], [-10, 0, 10], [10, 0, 10], [10, 0, -10]]},
               {"type": "quad", "material": "light", "vertices": [[3, 1, 0], [1, 1, 1], [-1, 1, 1], [-1, 1, 0]]}]})";
  const LightingScene scene(parse_scene(json, "trapezoid.json"));
  const std::vector<Vec3> light = {{3, 1, 0}, {1, 1, 1}, {-1, 1, 1}, {-1, 1, 0}};
  PathOptions options;
  for (const Vec3 p : {Vec3(0.5f, 0, 0.8f), Vec3(0.0f, 0, 0.2f), Vec3(2.5f, 0, -0.6f)}) {
    const double exact = 0.5 / kPi * RT_GRADED(polygon_irradiance)(p, Vec3(0, 1, 0), light, 3.0f);
    // A short ray straight down onto the point, from just above it (below the light).
    const Ray ray{p + Vec3(0, 0.01f, 0), Vec3(0, -1, 0)};
    for (const PathIntegrator i : kPathIntegrators) {
      options.integrator = i;
      const Estimate e = estimate(scene, ray, options, i == PathIntegrator::naive || i == PathIntegrator::russian_roulette ? 80000 : 20000);
      EXPECT_NEAR(e.mean, exact, 4.0 * e.standard_error) << integrator_name(i) << " at x = " << p.x;
      EXPECT_LT(e.standard_error, 0.02 * exact) << integrator_name(i) << " at x = " << p.x;
    }
  }
}

TEST(PathClosedForm, EmittersAreOneSided) {
  // The disk of the test above turned to face up, away from the floor: the floor sees only its
  // back, which emits nothing, so every integrator must return exactly 0 (light samples there have
  // cos theta' < 0, and BRDF samples that hit the back find no emission).
  const std::string json = R"({"camera": {"position": [3, 0.2, 0], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"floor": {"albedo": [0.5, 0.5, 0.5]}, "light": {"emission": [4, 4, 4], "albedo": [0, 0, 0]}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-10, 0, -10], [-10, 0, 10], [10, 0, 10], [10, 0, -10]]},
               {"type": "disk", "material": "light", "center": [0, 1, 0], "normal": [0, 1, 0], "radius": 0.5}]})";
  const LightingScene scene(parse_scene(json, "disk-up.json"));
  PathOptions options;
  for (const PathIntegrator i : kPathIntegrators) {
    options.integrator = i;
    const Estimate e = estimate(scene, Ray{Vec3(0.2f, 0.01f, 0), Vec3(0, -1, 0)}, options, 20000);
    EXPECT_EQ(e.mean, 0.0) << integrator_name(i);
  }
}

TEST(RussianRoulette, LeavesTheExpectationUnchanged) {
  // With roulette from the first bounce, and with a fixed depth far beyond where paths matter
  // (rho^64 is negligible), the means agree.
  const LightingScene scene = furnace(0.7f, 0.3f);
  const Ray ray{Vec3(0.0f), glm::normalize(Vec3(0.2f, 0.1f, 1.0f))};
  PathOptions fixed, roulette;
  fixed.integrator = PathIntegrator::naive;
  fixed.max_depth = 64;
  roulette.integrator = PathIntegrator::russian_roulette;
  roulette.roulette_start = 1;
  const Estimate a = estimate(scene, ray, fixed, 20000), b = estimate(scene, ray, roulette, 20000, 2);
  EXPECT_NEAR(a.mean, b.mean, 4.0 * std::hypot(a.standard_error, b.standard_error));
  EXPECT_NEAR(b.mean, 1.0, 4.0 * b.standard_error);
}

TEST(RussianRoulette, SurvivalIsTheLargestThroughputComponentUpTo095) {
  // The header's rule, P = min(0.95, max component): a path carrying a colour survives as often as
  // its strongest channel asks (a rarer survival only adds noise, and the tests of the mean above
  // cannot see noise), and even a path carrying everything ends now and then (P < 1).
  EXPECT_FLOAT_EQ(RT_GRADED(survival_probability)(Color(0.5f, 0.2f, 0.1f)), 0.5f);
  EXPECT_FLOAT_EQ(RT_GRADED(survival_probability)(Color(0.01f, 0.3f, 0.02f)), 0.3f);
  EXPECT_FLOAT_EQ(RT_GRADED(survival_probability)(Color(0.0f, 0.0f, 0.9f)), 0.9f);
  EXPECT_FLOAT_EQ(RT_GRADED(survival_probability)(Color(1.0f)), 0.95f);
  EXPECT_FLOAT_EQ(RT_GRADED(survival_probability)(Color(3.0f, 0.1f, 0.1f)), 0.95f);
}

// Veach's power heuristic (beta = 2) at the points where a slip shows: equal densities share
// evenly, a delta strategy (infinite density) takes everything, a strategy that cannot make the
// sample (density 0) takes nothing, and the two weights of one sample add up to 1.
TEST(PowerHeuristic, WeighsBySquaredDensitiesAndTrustsADeltaFully) {
  EXPECT_FLOAT_EQ(RT_GRADED(power_heuristic)(2.0f, 2.0f), 0.5f);
  EXPECT_FLOAT_EQ(RT_GRADED(power_heuristic)(3.0f, 1.0f), 0.9f);
  EXPECT_FLOAT_EQ(RT_GRADED(power_heuristic)(1.0f, 3.0f), 0.1f);
  EXPECT_EQ(RT_GRADED(power_heuristic)(kInfinity, 5.0f), 1.0f);
  EXPECT_EQ(RT_GRADED(power_heuristic)(kInfinity, 0.0f), 1.0f);
  EXPECT_EQ(RT_GRADED(power_heuristic)(0.0f, 4.0f), 0.0f);
  EXPECT_EQ(RT_GRADED(power_heuristic)(4.0f, 0.0f), 1.0f);
  EXPECT_EQ(RT_GRADED(power_heuristic)(0.0f, 0.0f), 0.0f) << "no strategy could make it: weight 0, not 0/0";
  for (const float a : {0.1f, 0.7f, 2.5f, 40.0f})
    for (const float b : {0.05f, 1.0f, 9.0f})
      EXPECT_NEAR(RT_GRADED(power_heuristic)(a, b) + RT_GRADED(power_heuristic)(b, a), 1.0f, 1e-6f);
}

TEST(PathRobustness, NoNanOrInfFromGrazingAndCornerPaths) {
  const SceneDescription description = load_scene(testing::source_path("assets/scenes/cornell-box.json"));
  const LightingScene scene(description);
  PathOptions options;
  const int bad = testing::subject([&] {
    Rng rng(5, 0, 0);
    int count = 0;
    for (const PathIntegrator i : kPathIntegrators) {
      options.integrator = i;
      for (int k = 0; k < 20000; ++k) {
        // From a box corner, along the walls and into the edges where two walls meet.
        const Vec3 origin(1e-3f * rng.uniform(), 548.8f * rng.uniform(), 1e-3f * rng.uniform());
        const Vec3 target(552.8f * rng.uniform(), 0.0f, 559.2f);
        const Color l = path_radiance(scene, Ray{origin, glm::normalize(target - origin)}, options, rng);
        count += is_finite(l) && min_component(l) >= 0.0f ? 0 : 1;
      }
    }
    return count;
  });
  EXPECT_EQ(bad, 0);
}

TEST(SampleGuard, CountsAndDropsBadSamples) {
  SampleGuard guard;
  EXPECT_EQ(guard(Color(1.0f, 2.0f, 3.0f)), Color(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(guard(Color(std::nanf(""), 1.0f, 1.0f)), Color(0.0f));
  EXPECT_EQ(guard(Color(kInfinity, 1.0f, 1.0f)), Color(0.0f));
  EXPECT_EQ(guard(Color(-1e-3f, 1.0f, 1.0f)), Color(0.0f));
  EXPECT_EQ(guard.dropped(), 3u);
}

}  // namespace
}  // namespace rt
