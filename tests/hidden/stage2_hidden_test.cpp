// Hidden tests of stage 2: both triangle tests on random triangles against barycentrics solved in
// double precision, and the optics at random angles against Snell's law and the Fresnel equations
// evaluated here.
#include "02-whitted/optics.h"
#include "02-whitted/triangle_ray.h"
#include "common/random.h"
#include "stage2/records.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::subject;

Vec3 random_point(Rng& rng, float scale) {
  return (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * scale;
}

TEST(HiddenTriangle, RandomTrianglesAgreeWithDoubleBarycentrics) {
  Rng rng(31337, 0, 0);
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 v0 = random_point(rng, 3), v1 = random_point(rng, 3), v2 = random_point(rng, 3);
    // Aim at a point with known barycentrics; well inside or well outside, never near an edge.
    const double b1 = 1.6 * rng.uniform() - 0.3, b2 = 1.6 * rng.uniform() - 0.3;
    const double b0 = 1.0 - b1 - b2;
    const double margin = std::min({b0, b1, b2});
    if (std::abs(margin) < 0.02) continue;
    const glm::dvec3 target = b0 * glm::dvec3(v0) + b1 * glm::dvec3(v1) + b2 * glm::dvec3(v2);
    const glm::dvec3 normal = glm::cross(glm::dvec3(v1 - v0), glm::dvec3(v2 - v0));
    const Vec3 origin = Vec3(target) + random_point(rng, 1) + Vec3(normal) * 0.5f;
    const glm::dvec3 to_target = target - glm::dvec3(origin);
    const Ray ray{origin, Vec3(glm::normalize(to_target))};
    if (std::abs(glm::dot(glm::normalize(normal), glm::normalize(to_target))) < 0.1) continue;  // near grazing
    for (TriangleMethod method : {TriangleMethod::moller_trumbore, TriangleMethod::watertight}) {
      const std::optional<TriangleHit> hit = subject([&] { return intersect_triangle(method, ray, v0, v1, v2, Interval::positive()); });
      ASSERT_EQ(hit.has_value(), margin > 0.0) << "ray " << i;
      if (!hit) continue;
      EXPECT_NEAR(hit->t, glm::length(to_target), 1e-3 * (1.0 + glm::length(to_target))) << "ray " << i;
      EXPECT_NEAR(hit->b1, b1, 2e-3) << "ray " << i;
      EXPECT_NEAR(hit->b2, b2, 2e-3) << "ray " << i;
    }
    inside += margin > 0.0 ? 1 : 0;
  }
  EXPECT_GT(inside, 400);
}

TEST(HiddenOptics, RandomAnglesObeySnellAndFresnel) {
  Rng rng(5150, 0, 0);
  const Vec3 n(0, 0, 1);
  for (int i = 0; i < 500; ++i) {
    const float eta_i = 1.0f + rng.uniform(), eta_t = 1.0f + rng.uniform();
    const float phi = 6.2831853f * rng.uniform(), cos_i = 0.05f + 0.95f * rng.uniform();
    const float sin_i = std::sqrt(1.0f - cos_i * cos_i);
    const Vec3 d(sin_i * std::cos(phi), sin_i * std::sin(phi), -cos_i);  // arriving from above

    const Vec3 r = subject([&] { return reflect(d, n); });
    EXPECT_NEAR(r.z, cos_i, 1e-5f);
    EXPECT_NEAR(r.x, d.x, 1e-5f);

    const double sin_t = eta_i * double(sin_i) / eta_t;
    const std::optional<Vec3> t = subject([&] { return refract(d, n, eta_i, eta_t); });
    ASSERT_EQ(t.has_value(), sin_t < 1.0) << "case " << i;
    const double fresnel = subject([&] { return fresnel_dielectric(cos_i, eta_i, eta_t); });
    if (!t) {
      EXPECT_NEAR(fresnel, 1.0, 1e-6);
      continue;
    }
    EXPECT_NEAR(std::sqrt(double(t->x) * t->x + double(t->y) * t->y), sin_t, 1e-4);
    EXPECT_LT(t->z, 0.0f);
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    const double rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    EXPECT_NEAR(fresnel, 0.5 * (rs * rs + rp * rp), 1e-5) << "case " << i;
  }
}

}  // namespace
}  // namespace rt
