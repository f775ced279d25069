// Hidden tests of stage 5: the furnace at an albedo and emission no visible test uses, with every
// integrator, and the two small formulas of the path tracer at random inputs.
#include "05-path-tracing/path_render.h"
#include "05-path-tracing/path_tracer.h"
#include "common/random.h"
#include "stage5/path_estimates.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

TEST(HiddenFurnace, OtherAlbedoAndEmission) {
  const LightingScene scene = furnace(0.3f, 1.4f, 1.5f);  // L = 2
  PathOptions options;
  options.max_depth = 3;
  const Ray ray{Vec3(0.4f, -0.2f, 0.1f), glm::normalize(Vec3(-0.3f, 0.8f, 0.5f))};
  for (const PathIntegrator integrator : kPathIntegrators) {
    options.integrator = integrator;
    const Estimate e = estimate(scene, ray, options, 20000, 17);
    // The naive integrator stops after D = 3 bounces: Le (1 - rho^(D+1)) / (1 - rho).
    const double exact = integrator == PathIntegrator::naive ? 1.4 * (1 - std::pow(0.3, 4)) / 0.7 : 2.0;
    EXPECT_NEAR(e.mean, exact, 4 * e.standard_error + 1e-5) << integrator_name(integrator);
    EXPECT_LT(e.standard_error, 0.02 * exact) << integrator_name(integrator);
  }
}

TEST(HiddenPathFormulas, PowerHeuristicAndSurvivalAtRandomInputs) {
  Rng rng(60606, 0, 0);
  for (int i = 0; i < 500; ++i) {
    const float a = 5.0f * rng.uniform(), b = 5.0f * rng.uniform();
    if (a + b > 0.0f) {
      EXPECT_NEAR(RT_GRADED(power_heuristic)(a, b), a * a / (a * a + b * b), 1e-6f);
    }
    const Color beta(2.0f * rng.uniform(), 2.0f * rng.uniform(), 2.0f * rng.uniform());
    const float p = RT_GRADED(survival_probability)(beta);
    EXPECT_GT(p, 0.0f);
    EXPECT_LE(p, 1.0f);
    // Larger throughput never survives less often.
    EXPECT_LE(p, RT_GRADED(survival_probability)(beta * 1.5f) + 1e-6f);
  }
}

}  // namespace
}  // namespace rt
