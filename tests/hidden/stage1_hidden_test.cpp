// Hidden tests of stage 1: the intersection tasks on random inputs, against roots computed in
// double precision here.
#include "01-ray-casting/plane_intersection.h"
#include "01-ray-casting/sphere_intersection.h"
#include "common/random.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::subject;

// The nearest root of |o + t d - c|^2 = r^2 with t > 0, in double; nullopt for a miss.
std::optional<double> sphere_root(const Ray& ray, const Sphere& s) {
  const glm::dvec3 o(ray.origin), d(ray.direction), c(s.center);
  const double a = glm::dot(d, d), b = glm::dot(o - c, d), k = glm::dot(o - c, o - c) - double(s.radius) * s.radius;
  const double disc = b * b - a * k;
  if (disc < 0.0) return std::nullopt;
  const double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
  if (t0 > 1e-6) return t0;
  if (t1 > 1e-6) return t1;
  return std::nullopt;
}

TEST(HiddenSphere, RandomRaysAgreeWithDoubleRoots) {
  Rng rng(4242, 0, 0);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Sphere s{Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 6.0f - 3.0f, 0.3f + 1.5f * rng.uniform()};
    const Vec3 target = s.center + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * s.radius * 1.3f;
    const Vec3 origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 20.0f - 10.0f;
    const Ray ray{origin, glm::normalize(target - origin)};
    const std::optional<double> expected = sphere_root(ray, s);
    for (auto intersect : {intersect_sphere_textbook, intersect_sphere_stable}) {
      const std::optional<float> t = subject([&] { return intersect(ray, s, Interval::positive()); });
      // Grazing rays (the discriminant near 0) may go either way; elsewhere hit or miss must agree.
      const glm::dvec3 oc = glm::dvec3(origin) - glm::dvec3(s.center);
      const double b = glm::dot(oc, glm::dvec3(ray.direction));
      const double disc = b * b - (glm::dot(oc, oc) - double(s.radius) * s.radius);
      if (std::abs(disc) < 1e-3 * s.radius * s.radius) continue;
      ASSERT_EQ(t.has_value(), expected.has_value()) << "ray " << i;
      if (t) {
        EXPECT_NEAR(*t, *expected, 1e-4 * (1.0 + *expected)) << "ray " << i;
      }
    }
    hits += expected ? 1 : 0;
  }
  EXPECT_GT(hits, 500);
}

TEST(HiddenPlane, RandomPlanesAgreeWithDouble) {
  Rng rng(977, 0, 0);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Plane plane{Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - 2.0f,
                      glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f)};
    const Ray ray{Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 8.0f - 4.0f,
                  glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f)};
    const double denom = glm::dot(glm::dvec3(ray.direction), glm::dvec3(plane.normal));
    if (std::abs(denom) < 0.05) continue;
    const double t = glm::dot(glm::dvec3(plane.point) - glm::dvec3(ray.origin), glm::dvec3(plane.normal)) / denom;
    const std::optional<float> got = subject([&] { return intersect_plane(ray, plane, Interval{0.001f, 100.0f}); });
    if (t < 0.01 || t > 99.0) {
      if (t < -0.01 || t > 101.0) {
        EXPECT_FALSE(got) << "ray " << i;
      }
      continue;
    }
    ASSERT_TRUE(got) << "ray " << i;
    EXPECT_NEAR(*got, t, 1e-4 * (1.0 + t));
    ++hits;
  }
  EXPECT_GT(hits, 300);
}

}  // namespace
}  // namespace rt
