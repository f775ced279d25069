// Stage 5: paths under an environment light. What the camera and a mirror see of it exactly; the
// white furnace and the floor under a bright patch of sky (closed forms, as in stage 4's tests)
// for every integrator; and MIS, which counts the environment found by light sampling and by the
// BRDF each with its weight, agreeing with next-event estimation alone.
#include "05-path-tracing/path_render.h"
#include "path_estimates.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <memory>

namespace rt {
namespace {

Environment peaked_sky(float bright, float dim) {
  // 32 x 16 texels, dim but for rows 2-3 (theta 22.5-45 degrees) and columns 4-7 (phi 45-90).
  auto image = std::make_shared<Image>(32, 16, Color(dim));
  for (int y = 2; y < 4; ++y)
    for (int x = 4; x < 8; ++x) image->at(x, y) = Color(bright);
  Environment e;
  e.image = image;
  return e;
}

SceneDescription scene_of(Material material, Geometry geometry, Environment environment) {
  SceneDescription d;
  d.source = "test";
  d.materials.push_back(material);
  d.shapes.push_back(Shape{"", std::move(geometry), 0});
  d.environment = std::move(environment);
  return d;
}

const Quad kFloor{{Vec3(-10, 0, -10), Vec3(-10, 0, 10), Vec3(10, 0, 10), Vec3(10, 0, -10)}};

TEST(EnvironmentPaths, CameraAndMirrorSeeTheEnvironmentExactly) {
  Material mirror;
  mirror.type = MaterialType::mirror;
  mirror.reflectance = Color(0.5f, 0.25f, 1.0f);
  const LightingScene scene(scene_of(mirror, kFloor, peaked_sky(50.0f, 0.5f)));
  for (const PathIntegrator integrator :
       {PathIntegrator::naive, PathIntegrator::next_event_estimation, PathIntegrator::mis}) {
    PathOptions options;
    options.integrator = integrator;
    Rng rng(1, 0, 0);
    // Straight into the sky, in the bright patch (theta 30 degrees, phi 60 degrees).
    const Vec3 up(std::sin(radians(30.0f)) * std::cos(radians(60.0f)), std::cos(radians(30.0f)),
                  std::sin(radians(30.0f)) * std::sin(radians(60.0f)));
    EXPECT_EQ(RT_GRADED(path_radiance)(scene, Ray{Vec3(0, 1, 0), up}, options, rng), Color(50.0f));
    // Down onto the mirror floor, whose reflection rises into the patch: the reflectance times it,
    // counted whole (light sampling cannot serve a mirror, so no weight may shrink it).
    const Vec3 down(up.x, -up.y, up.z);
    EXPECT_EQ(RT_GRADED(path_radiance)(scene, Ray{Vec3(0, 1, 0) - 2.0f * down, down}, options, rng),
              Color(25.0f, 12.5f, 50.0f))
        << integrator_name(integrator);
  }
}

const PathIntegrator (&kIntegrators)[4] = kPathIntegrators;

TEST(EnvironmentPaths, WithoutAnEnvironmentTheBackgroundIsSeenAndLightsWhole) {
  // A background is no light sample's, so every integrator counts it whole wherever a path leaves:
  // straight into the sky it is the background itself, and a Lambertian floor under it, which sees
  // nothing but sky above, sends back rho B.
  SceneDescription d;
  d.source = "background";
  Material floor;
  floor.albedo = Color(0.5f);
  d.materials.push_back(floor);
  d.shapes.push_back(Shape{"floor", kFloor, 0});
  d.background = Color(0.25f, 0.5f, 1.0f);
  const LightingScene scene(d);
  const Ray down{Vec3(0, 1, 0), glm::normalize(Vec3(0.3f, -1.0f, 0.2f))};
  ASSERT_TRUE(RT_GRADED(scene.closest_hit)(down, Interval::positive()).has_value()) << "the ray must hit the floor";
  for (const PathIntegrator integrator : kIntegrators) {
    PathOptions options;
    options.integrator = integrator;
    Rng rng(1, 0, 0);
    EXPECT_EQ(RT_GRADED(path_radiance)(scene, Ray{Vec3(0, 1, 0), Vec3(0, 1, 0)}, options, rng), d.background)
        << integrator_name(integrator);
    for (int channel = 0; channel < 3; ++channel) {
      const Estimate m = estimate(scene, down, options, 4000, 1, channel);
      EXPECT_NEAR(m.mean, 0.5 * d.background[channel], 4.0 * m.standard_error + 1e-6)
          << integrator_name(integrator) << ", channel " << channel;
    }
  }
}

TEST(EnvironmentPaths, WhiteFurnaceForEveryIntegrator) {
  // A Lambertian sphere of albedo rho under radiance 1 everywhere reflects rho.
  for (const float rho : {1.0f, 0.5f}) {
    Material ball;
    ball.albedo = Color(rho);
    Environment white;
    white.scale = Color(1.0f);
    const LightingScene scene(scene_of(ball, Sphere{Vec3(0.0f), 1.0f}, white));
    const Ray ray{Vec3(0.3f, 0.4f, 3.0f), Vec3(0, 0, -1)};
    ASSERT_TRUE(RT_GRADED(scene.closest_hit)(ray, Interval::positive()).has_value()) << "the ray must hit the ball";
    for (const PathIntegrator integrator : kIntegrators) {
      PathOptions options;
      options.integrator = integrator;
      const Estimate m = estimate(scene, ray, options, 20000);
      EXPECT_NEAR(m.mean, rho, 4.0 * m.standard_error + 1e-6) << integrator_name(integrator) << " +- " << m.standard_error;
      EXPECT_LT(m.standard_error, 0.02);
    }
  }
}

TEST(EnvironmentPaths, FloorUnderABrightPatchMatchesTheClosedForm) {
  // rho E / pi with E = L (phi1 - phi0) (sin^2 theta1 - sin^2 theta0) / 2 (stage 4's BrightPatch).
  constexpr float kL = 50.0f, kRho = 0.5f;
  Material floor;
  floor.albedo = Color(kRho);
  const LightingScene scene(scene_of(floor, kFloor, peaked_sky(kL, 0.0f)));
  const double s1 = std::sin(kPi / 4.0), s0 = std::sin(kPi / 8.0);
  const double expected = kRho / kPi * kL * (kPi / 4.0) * (s1 * s1 - s0 * s0) / 2.0;
  const Ray ray{Vec3(2.0f, 1.0f, 0.5f), glm::normalize(Vec3(-2.0f, -1.0f, -0.5f))};
  for (const PathIntegrator integrator : kIntegrators) {
    PathOptions options;
    options.integrator = integrator;
    const Estimate m = estimate(scene, ray, options, 40000);
    EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error) << integrator_name(integrator) << " +- " << m.standard_error;
    EXPECT_LT(m.standard_error, 0.1 * expected) << integrator_name(integrator);
  }
}

TEST(EnvironmentPaths, MisAgreesWithNextEventEstimationOnAGlossyFloor) {
  // A sharp Phong lobe pointing at the patch: BRDF samples find it often, light samples too; MIS
  // must count it once. Without its weight on the escaped path it would count it nearly twice.
  Material glossy;
  glossy.type = MaterialType::phong;
  glossy.albedo = Color(0.2f);
  glossy.specular = Color(0.7f);
  glossy.shininess = 300.0f;
  const LightingScene scene(scene_of(glossy, kFloor, peaked_sky(50.0f, 0.05f)));
  // A view whose mirror direction is the patch's centre (theta 33.75, phi 67.5 degrees).
  const float theta = radians(33.75f), phi = radians(67.5f);
  const Vec3 r(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  const Ray ray{Vec3(-r.x, r.y, -r.z) * 2.0f, glm::normalize(Vec3(r.x, -r.y, r.z))};
  ASSERT_TRUE(RT_GRADED(scene.closest_hit)(ray, Interval::positive()).has_value()) << "the ray must hit the floor";
  PathOptions nee, mis;
  nee.integrator = PathIntegrator::next_event_estimation;
  mis.integrator = PathIntegrator::mis;
  const Estimate a = estimate(scene, ray, nee, 40000, 1), b = estimate(scene, ray, mis, 40000, 2);
  EXPECT_NEAR(a.mean, b.mean, 4.0 * std::hypot(a.standard_error, b.standard_error))
      << "nee " << a.mean << " +- " << a.standard_error << ", mis " << b.mean << " +- " << b.standard_error;
  EXPECT_LT(b.standard_error, 0.05 * b.mean);
}

}  // namespace
}  // namespace rt
