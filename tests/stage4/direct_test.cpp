// Stage 4: Monte Carlo direct lighting against closed forms. A Lambertian floor of albedo rho under
// an emitter of radiance L, seen at a point p straight below the emitter's centre, sends back
// L_r = rho E / pi with E = pi L F (closed_form.h); every estimator must find that value within its
// confidence interval, and with a small enough interval that the test means something.
#include "04-radiometry/direct_lighting.h"
#include "closed_form.h"
#include "direct_estimators.h"
#include "stage4/records.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <sstream>

namespace rt {
namespace {

constexpr float kAlbedo = 0.5f;
const Vec3 kAbove(1.5f, 1.2f, 0.0f);  // a viewpoint whose mirror direction off the floor rises at 39 degrees

using testing::Estimate;
using testing::estimator_name;
using testing::kEstimators;

// A 20 x 20 floor at y = 0 with material `floor`, plus the given shapes and lights.
LightingScene floor_scene(const std::string& floor_material, const std::string& emitters, const std::string& lights = "[]") {
  const std::string json = R"({"camera": {"position": [3, 0.2, 0], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"floor": )" + floor_material + R"(, "light": {"emission": [4, 4, 4]}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-10, 0, -10], [-10, 0, 10], [10, 0, 10], [10, 0, -10]]})" +
                           (emitters.empty() ? "" : ", " + emitters) + R"(],
    "lights": )" + lights + "}";
  return LightingScene(parse_scene(json, "closed-form.json"));
}

// The radiance along one fixed ray to the floor point `target`, by default the origin seen from a
// low position so that the ray passes under every emitter: `samples` independent estimates, their
// mean and standard error.
Estimate estimate_at(const LightingScene& scene, DirectEstimator estimator, int samples,
                     Vec3 origin = Vec3(3.0f, 0.2f, 0.0f), Vec3 target = Vec3(0.0f)) {
  constexpr std::uint64_t seed = 1;
  const Ray ray{origin, glm::normalize(target - origin)};
  DirectOptions options;
  options.estimator = estimator;
  return testing::subject([&] {
    testing::SampleMean m;
    for (int k = 0; k < samples; ++k) {
      Rng rng(seed, 0, std::uint64_t(k));
      m.add(direct_radiance(scene, ray, options, rng).x);
    }
    return m.estimate();
  });
}

void expect_every_estimator_finds(const LightingScene& scene, double exact, int samples) {
  for (const DirectEstimator e : kEstimators) {
    const Estimate est = estimate_at(scene, e, samples);
    EXPECT_NEAR(est.mean, exact, 4.0 * est.standard_error + 1e-5 * exact) << estimator_name(e);
    EXPECT_LT(est.standard_error, 0.02 * exact) << estimator_name(e) << ": too noisy to mean anything";
  }
}

TEST(DirectClosedForm, PointLightInverseSquareAndCosineLaw) {
  // I = 8 at height 2 straight above, and I = 4 at distance 2 and 60 degrees off the normal:
  // E = 8 / 4 + 4 cos(60) / 4 = 2.5, L_r = rho E / pi. Deterministic for every estimator. At the
  // origin and, lights and all moved along the floor, at a point away from it (where a direction
  // to the light taken from the origin instead of from the point is wrong).
  const float s = std::sin(radians(60.0f)) * 2.0f, c = std::cos(radians(60.0f)) * 2.0f;
  for (const Vec3 p : {Vec3(0.0f), Vec3(1.25f, 0.0f, -0.75f)}) {
    const auto at = [&](float x, float y, float z) {
      std::ostringstream out;
      out.precision(9);
      out << '[' << p.x + x << ", " << y << ", " << p.z + z << ']';
      return out.str();
    };
    const LightingScene scene = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})", "",
                                            R"([{"type": "point", "position": )" + at(0, 2, 0) + R"(, "intensity": [8, 8, 8]},
                                                {"type": "point", "position": )" + at(0, c, s) + R"(, "intensity": [4, 4, 4]}])");
    const double exact = kAlbedo * 2.5 / kPi;
    for (const DirectEstimator e : kEstimators) {
      const Estimate est = estimate_at(scene, e, 16, p + Vec3(3.0f, 0.2f, 0.0f), p);
      EXPECT_NEAR(est.mean, exact, 1e-5 * exact) << estimator_name(e) << " at " << p.x << ", " << p.z;
      EXPECT_LT(est.standard_error, 1e-6) << estimator_name(e);
    }
  }
}

TEST(DirectClosedForm, SquareEmitter) {
  // A 1 x 1 square at height 1, centred above p, facing down: L_r = rho L F.
  const LightingScene scene = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})",
                                          R"({"type": "quad", "material": "light",
      "vertices": [[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]})");
  expect_every_estimator_finds(scene, kAlbedo * 4.0 * testing::factor_to_centred_square(1.0, 1.0), 40000);
}

TEST(DirectClosedForm, CoaxialDiskEmitter) {
  const LightingScene scene = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})",
                                          R"({"type": "disk", "material": "light", "center": [0, 1, 0],
      "normal": [0, -1, 0], "radius": 0.5})");
  expect_every_estimator_finds(scene, kAlbedo * 4.0 * testing::factor_to_coaxial_disk(0.5, 1.0), 40000);
}

TEST(DirectClosedForm, SphereEmitter) {
  const LightingScene scene = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})",
                                          R"({"type": "sphere", "material": "light", "center": [0, 1.5, 0], "radius": 0.6})");
  expect_every_estimator_finds(scene, kAlbedo * 4.0 * testing::factor_to_sphere_on_normal(0.6, 1.5), 40000);
}

TEST(DirectClosedForm, OneSidedEmitterLightsNothingBehindIt) {
  // The square faces up, away from the floor: no estimator sees any of its light.
  const LightingScene scene = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})",
                                          R"({"type": "quad", "material": "light",
      "vertices": [[-0.5, 1, -0.5], [-0.5, 1, 0.5], [0.5, 1, 0.5], [0.5, 1, -0.5]]})");
  for (const DirectEstimator e : kEstimators) EXPECT_EQ(estimate_at(scene, e, 1000).mean, 0.0) << estimator_name(e);
}

TEST(DirectEstimators, AgreeOnGlossySurfaces) {
  // No closed form, but all four estimate the same integral: their means agree within error.
  for (const char* floor : {R"({"type": "phong", "albedo": [0.2, 0.2, 0.2], "specular": [0.7, 0.7, 0.7], "shininess": 20})",
                            R"({"type": "microfacet", "specular": [0.9, 0.9, 0.9], "roughness": 0.3})"}) {
    const LightingScene scene = floor_scene(floor, R"({"type": "quad", "material": "light",
      "vertices": [[-2.5, 1.5, -0.5], [-1.5, 1.5, -0.5], [-1.5, 1.5, 0.5], [-2.5, 1.5, 0.5]]})");
    std::vector<Estimate> estimates;
    // Seen from above, so the mirror direction of the view points into the light.
    for (const DirectEstimator e : kEstimators) estimates.push_back(estimate_at(scene, e, 60000, kAbove));
    EXPECT_GT(estimates.back().mean, 0.05) << floor;  // the highlight is in view
    for (size_t i = 0; i < estimates.size(); ++i)
      for (size_t j = i + 1; j < estimates.size(); ++j) {
        const double se = std::hypot(estimates[i].standard_error, estimates[j].standard_error);
        EXPECT_NEAR(estimates[i].mean, estimates[j].mean, 4.0 * se) << floor << ": " << estimator_name(kEstimators[i]) << " vs "
                                                                  << estimator_name(kEstimators[j]);
      }
  }
}

TEST(DirectEstimators, LightSamplingWinsForSmallLightsBrdfSamplingForSharpLobes) {
  // A small light over a diffuse floor: light sampling has far less variance.
  const LightingScene small = floor_scene(R"({"albedo": [0.5, 0.5, 0.5]})", R"({"type": "disk", "material": "light",
      "center": [0, 1, 0], "normal": [0, -1, 0], "radius": 0.05})");
  const Estimate by_light = estimate_at(small, DirectEstimator::light, 4000);
  const Estimate by_cosine = estimate_at(small, DirectEstimator::cosine_hemisphere, 4000);
  EXPECT_LT(by_light.standard_error * 10.0, by_cosine.standard_error);
  // A large light seen in a sharp glossy lobe: BRDF sampling has less variance.
  const LightingScene glossy = floor_scene(R"({"type": "phong", "albedo": [0, 0, 0], "specular": [0.9, 0.9, 0.9], "shininess": 2000})",
                                           R"({"type": "quad", "material": "light",
      "vertices": [[-20, 3, -10], [0, 3, -10], [0, 3, 10], [-20, 3, 10]]})");
  const Estimate glossy_light = estimate_at(glossy, DirectEstimator::light, 4000, kAbove);
  const Estimate glossy_brdf = estimate_at(glossy, DirectEstimator::brdf, 4000, kAbove);
  EXPECT_LT(glossy_brdf.standard_error * 3.0, glossy_light.standard_error);
}

TEST(DirectDelta, EveryEstimatorSeesALightInAMirror) {
  // A mirror floor reflects the ray up into a disk emitter of radiance 4: 0.8 x 4, exactly.
  const LightingScene scene = floor_scene(R"({"type": "mirror", "reflectance": [0.8, 0.8, 0.8]})",
                                          R"({"type": "disk", "material": "light", "center": [-3, 0.2, 0],
      "normal": [1, 0, 0], "radius": 0.5})");
  for (const DirectEstimator e : kEstimators) {
    const Estimate est = estimate_at(scene, e, 8);
    EXPECT_NEAR(est.mean, 3.2, 1e-5) << estimator_name(e);
  }
}

// The exact boundary of light sampling's contract: a sample whose density is exactly 0 contributes
// nothing. Here the density is 0 while the light is bright and in view: the shading point lies
// 10^-20 in front of the corner of a quad light 1000 units wide, which u = (0, 0) picks, so
// p_A d^2 / cos = 10^-6 * 10^-40 underflows to 0 and Le f cos / p would be infinite. "pdf > 0" written as "pdf >= 0" survived every test
// until this one; a pdf of 0 elsewhere (a point behind the light) comes with Le = 0 as well.
TEST(DirectRobustness, ALightSampleOfDensityZeroContributesNothing) {
  const std::string json = R"({"camera": {"position": [3, 1, 0], "look_at": [0, 0, 0], "vfov": 40},
    "materials": {"light": {"emission": [4, 4, 4]}},
    "shapes": [{"type": "quad", "material": "light", "vertices": [[0, 0, 0], [0, 0, 1000], [1000, 0, 1000], [1000, 0, 0]]}]})";
  const LightingScene scene(parse_scene(json, "corner.json"));
  ASSERT_EQ(scene.emitters().size(), 1u);
  Hit hit;
  hit.point = Vec3(0.0f, 1e-20f, 0.0f);
  hit.normal = hit.shading_normal = Vec3(0.0f, -1.0f, 0.0f);  // facing the light below it
  const Frame frame = Frame::from_normal(hit.normal);
  const ShadingPoint at{hit, Bsdf(LambertBrdf{Color(0.5f)}), frame, Vec3(0.0f, 0.0f, 1.0f)};
  const AreaEmitter& light = scene.emitters()[0];
  ASSERT_GT(max_component(light.radiance_towards(Vec3(0.0f), hit.point)), 0.0f) << "the light faces the point";
  ASSERT_EQ(RT_GRADED(light.sample)(hit.point, Vec2(0.0f)).pdf, 0.0f) << "the density underflows to exactly 0";
  const DirectLightSample sample = RT_GRADED(sample_direct_light)(scene, at, 0.5f, Vec2(0.0f), OffsetPolicy{});
  EXPECT_EQ(sample.value, Color(0.0f));
  // Just off the boundary the same light is sampled as usual: finite and lit.
  const DirectLightSample near = RT_GRADED(sample_direct_light)(scene, at, 0.5f, Vec2(0.5f), OffsetPolicy{});
  EXPECT_TRUE(is_finite(near.value));
  EXPECT_GT(near.pdf, 0.0f);
}

TEST(DirectRobustness, GrazingAndCornerRaysStayFinite) {
  const LightingScene scene = floor_scene(R"({"type": "microfacet", "specular": [0.9, 0.9, 0.9], "roughness": 0.01})",
                                          R"({"type": "sphere", "material": "light", "center": [0, 0.5, 0], "radius": 0.5},
      {"type": "quad", "material": "light", "vertices": [[-1, 1e-4, -1], [1, 1e-4, -1], [1, 1e-4, 1], [-1, 1e-4, 1]]})");
  DirectOptions options;
  Rng rng(3, 0, 0);
  for (const DirectEstimator e : kEstimators) {
    options.estimator = e;
    for (int k = 0; k < 20000; ++k) {
      // Rays from all around, many nearly parallel to the floor or aimed at the sphere's contact.
      const Vec3 origin = Vec3(4.0f, 0.0f, 0.0f) * (1.0f + rng.uniform()) + Vec3(0.0f, 1e-3f * rng.uniform(), 0.0f);
      const Vec3 target(rng.uniform() - 0.5f, 0.0f, rng.uniform() - 0.5f);
      const Color l = direct_radiance(scene, Ray{origin, glm::normalize(target - origin)}, options, rng);
      ASSERT_TRUE(is_finite(l)) << estimator_name(e);
      ASSERT_GE(min_component(l), 0.0f) << estimator_name(e);
    }
  }
}

}  // namespace
}  // namespace rt
