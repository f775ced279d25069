#include "01-ray-casting/local_shading.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::subject;

// A grey Lambertian floor (albedo 0.5) at y = 0 and one point light of intensity 4 W/sr at height 2.
SceneDescription floor_scene(Vec3 light_position, bool with_blocker = false) {
  SceneDescription d;
  d.source = "test";
  Material grey;
  grey.albedo = Color(0.5f);
  d.materials.push_back(grey);
  d.shapes.push_back(Shape{"floor", Plane{Vec3(0), Vec3(0, 1, 0)}, 0});
  if (with_blocker) d.shapes.push_back(Shape{"blocker", Sphere{Vec3(0, 1, 0), 0.25f}, 0});
  d.lights.push_back(PointLight{light_position, Color(4.0f)});
  return d;
}

Color shade_floor_at(const RayCastingScene& scene, Vec3 point) {
  const Ray view{point + Vec3(0, 3, -3), glm::normalize(Vec3(0, -3, 3))};
  const std::optional<Color> shaded = subject([&]() -> std::optional<Color> {
    const std::optional<Hit> hit = scene.closest_hit(Ray{point + Vec3(0, 1, 0), Vec3(0, -1, 0)}, Interval::positive());
    if (!hit) return std::nullopt;
    return shade_local(scene, *hit, -view.direction);
  });
  if (!shaded) {
    ADD_FAILURE() << "the ray straight down onto the floor hit nothing (task stage1.scene.closest_hit)";
    return Color(-1.0f);
  }
  return *shaded;
}

TEST(LocalShading, LambertUnderAPointLightRightAbove) {
  // L = (rho / pi) * I * cos(theta) / r^2 = (0.5 / pi) * 4 * 1 / 4.
  const RayCastingScene scene(floor_scene(Vec3(0, 2, 0)));
  const Color L = shade_floor_at(scene, Vec3(0));
  EXPECT_NEAR(L.r, 0.5f / kPi, 1e-6f);
  EXPECT_EQ(L.r, L.g);
}

TEST(LocalShading, InverseSquareAndCosineLaws) {
  // At x = 1: r^2 = 5 and cos(theta) = 2 / sqrt(5).
  const RayCastingScene scene(floor_scene(Vec3(0, 2, 0)));
  const Color L = shade_floor_at(scene, Vec3(1, 0, 0));
  EXPECT_NEAR(L.r, 0.5f / kPi * 4.0f * (2.0f / std::sqrt(5.0f)) / 5.0f, 1e-6f);
  // At x = 4: r^2 = 20 and cos(theta) = 2 / sqrt(20).
  const Color far = shade_floor_at(scene, Vec3(4, 0, 0));
  EXPECT_NEAR(far.r, 0.5f / kPi * 4.0f * (2.0f / std::sqrt(20.0f)) / 20.0f, 1e-6f);
}

TEST(LocalShading, ShadowRayBlocksTheLight) {
  const RayCastingScene scene(floor_scene(Vec3(0, 2, 0), /*with_blocker=*/true));
  EXPECT_EQ(shade_floor_at(scene, Vec3(0)), Color(0.0f));
  EXPECT_GT(shade_floor_at(scene, Vec3(2, 0, 0)).r, 0.0f) << "outside the shadow";
}

TEST(LocalShading, AnObjectBeyondTheLightCastsNoShadow) {
  // The shadow ray ends at the light: a sphere above it (on the same line, farther from the floor)
  // must not darken the floor, nor must one just beyond the light's distance.
  for (const float centre_height : {3.0f, 2.3f}) {
    SceneDescription d = floor_scene(Vec3(0, 2, 0));
    d.shapes.push_back(Shape{"above the light", Sphere{Vec3(0, centre_height, 0), 0.25f}, 0});
    const RayCastingScene scene(d);
    EXPECT_NEAR(shade_floor_at(scene, Vec3(0)).r, 0.5f / kPi, 1e-6f) << "sphere centred at height " << centre_height;
  }
}

TEST(LocalShading, LightBelowATwoSidedSurfaceDoesNotLeakThrough) {
  // Seen from above, the floor's shading normal faces up; a light underneath gives nothing.
  const RayCastingScene scene(floor_scene(Vec3(0, -2, 0)));
  EXPECT_EQ(shade_floor_at(scene, Vec3(0)), Color(0.0f));
}

TEST(LocalShading, NoSelfShadowingOnACurvedSurface) {
  // The lit side of a sphere must not shadow itself (shadow acne).
  SceneDescription d;
  d.source = "test";
  d.materials.push_back(Material{});
  d.shapes.push_back(Shape{"ball", Sphere{Vec3(0, 0, 5), 1.0f}, 0});
  d.lights.push_back(PointLight{Vec3(0, 0, 0), Color(1.0f)});
  const RayCastingScene scene(d);
  for (float x = -0.6f; x <= 0.6f; x += 0.05f) {
    const Ray ray{Vec3(x, 0.1f, 0), Vec3(0, 0, 1)};
    const std::optional<Color> shaded = subject([&]() -> std::optional<Color> {
      const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
      if (!hit) return std::nullopt;
      return shade_local(scene, *hit, -ray.direction);
    });
    ASSERT_TRUE(shaded) << "x = " << x;
    EXPECT_GT(shaded->r, 0.0f) << "x = " << x;
  }
}

TEST(LocalShading, EmissionOnlyFromTheFrontFace) {
  SceneDescription d = floor_scene(Vec3(0, 2, 0));
  d.materials[0].emission = Color(3.0f);
  d.lights.clear();
  const RayCastingScene scene(d);
  const std::optional<Hit> above = subject([&] {
    return scene.closest_hit(Ray{Vec3(0, 1, 0), Vec3(0, -1, 0)}, Interval::positive());
  });
  ASSERT_TRUE(above);
  EXPECT_EQ(subject([&] { return shade_local(scene, *above, Vec3(0, 1, 0)); }), Color(3.0f));
  const std::optional<Hit> below = subject([&] {
    return scene.closest_hit(Ray{Vec3(0, -1, 0), Vec3(0, 1, 0)}, Interval::positive());
  });
  ASSERT_TRUE(below);
  EXPECT_FALSE(below->front_face);
  EXPECT_EQ(subject([&] { return shade_local(scene, *below, Vec3(0, -1, 0)); }), Color(0.0f));
}

TEST(BlinnPhong, LambertOnlyWithoutSpecular) {
  Material m;
  m.albedo = Color(0.3f, 0.6f, 0.9f);
  const Color f = subject(
      [&] { return blinn_phong_brdf(m, m.albedo, Vec3(0, 0, 1), Vec3(0, 0, 1), glm::normalize(Vec3(1, 0, 1))); });
  EXPECT_NEAR(f.g, 0.6f / kPi, 1e-7f);
}

TEST(BlinnPhong, NormalizedLobeAtAndAwayFromTheMirrorDirection) {
  Material m;
  m.albedo = Color(0.0f);
  m.specular = Color(1.0f);
  m.shininess = 20.0f;
  const Vec3 n(0, 0, 1);
  // wi and wo mirror each other about n: h = n, the lobe's peak (s + 8) / (8 pi).
  const Vec3 wi = glm::normalize(Vec3(1, 0, 1)), wo = glm::normalize(Vec3(-1, 0, 1));
  EXPECT_NEAR(subject([&] { return blinn_phong_brdf(m, m.albedo, n, wo, wi); }).r, 28.0f / (8.0f * kPi), 1e-5f);
  // wo = n, wi at 60 degrees: h is 30 degrees from n, so the lobe is (28 / 8pi) cos(30)^20.
  const Vec3 wi60(std::sin(radians(60.0f)), 0, std::cos(radians(60.0f)));
  EXPECT_NEAR(subject([&] { return blinn_phong_brdf(m, m.albedo, n, n, wi60); }).r,
              28.0f / (8.0f * kPi) * std::pow(std::cos(radians(30.0f)), 20.0f), 1e-5f);
}

TEST(BlinnPhong, Reciprocity) {
  Material m;
  m.specular = Color(0.5f);
  m.shininess = 50.0f;
  const Vec3 n(0, 0, 1), a = glm::normalize(Vec3(0.3f, 0.2f, 1)), b = glm::normalize(Vec3(-0.5f, 0.1f, 0.7f));
  EXPECT_EQ(subject([&] { return blinn_phong_brdf(m, m.albedo, n, a, b); }),
            subject([&] { return blinn_phong_brdf(m, m.albedo, n, b, a); }));
}

}  // namespace
}  // namespace rt
