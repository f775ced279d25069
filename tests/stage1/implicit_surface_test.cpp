#include "01-ray-casting/implicit_surface.h"
#include "common/random.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {

inline auto record_fields(ImplicitHit& h) { return std::tie(h.t, h.steps); }

namespace {

using testing::subject;

// Ring radius R = 2, tube radius r = 0.5, lying in the xz-plane.
const TorusSurface kTorus(Torus{Vec3(0), Vec3(0, 1, 0), 2.0f, 0.5f});

TEST(Torus, DistanceIsExactAtKnownPoints) {
  EXPECT_FLOAT_EQ(kTorus.distance(Vec3(2, 0, 0)), -0.5f);    // on the core circle
  EXPECT_FLOAT_EQ(kTorus.distance(Vec3(0, 0, 0)), 1.5f);     // centre of the hole
  EXPECT_FLOAT_EQ(kTorus.distance(Vec3(0, 0, -4)), 1.5f);    // outside the ring
  EXPECT_FLOAT_EQ(kTorus.distance(Vec3(2, 3, 0)), 2.5f);     // above the tube
  EXPECT_NEAR(kTorus.distance(Vec3(0, 5, 0)), std::sqrt(29.0f) - 0.5f, 1e-6f);  // on the axis
}

TEST(Torus, GradientIsTheTrueDerivative) {
  // A central difference of the distance agrees with the gradient (length 1 for a distance).
  const Vec3 p(1.1f, 0.7f, -2.3f);
  const float h = 1e-3f;
  const Vec3 numeric((kTorus.distance(p + Vec3(h, 0, 0)) - kTorus.distance(p - Vec3(h, 0, 0))) / (2 * h),
                     (kTorus.distance(p + Vec3(0, h, 0)) - kTorus.distance(p - Vec3(0, h, 0))) / (2 * h),
                     (kTorus.distance(p + Vec3(0, 0, h)) - kTorus.distance(p - Vec3(0, 0, h))) / (2 * h));
  EXPECT_NEAR(glm::length(kTorus.gradient(p) - numeric), 0.0f, 1e-3f);
  EXPECT_NEAR(glm::length(kTorus.gradient(p)), 1.0f, 1e-6f);
}

TEST(Torus, GradientIsTheOutwardNormal) {
  const Vec3 n = glm::normalize(kTorus.gradient(Vec3(0, 0, -2.5f)));
  EXPECT_NEAR(glm::length(n - Vec3(0, 0, -1)), 0.0f, 1e-6f);
  const Vec3 top = glm::normalize(kTorus.gradient(Vec3(2, 0.5f, 0)));
  EXPECT_NEAR(glm::length(top - Vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_TRUE(is_finite(kTorus.gradient(Vec3(0, 1, 0)))) << "defined on the axis too";
  const TorusSurface diagonal(Torus{Vec3(0), glm::normalize(Vec3(1, 1, 1)), 2.0f, 0.5f});
  // At the centre f = sqrt(R^2 + h^2) - r is flat along the axis and falls at rate 1 in every
  // radial direction: a valid gradient there is a unit vector perpendicular to the axis.
  const Vec3 at_centre = diagonal.gradient(Vec3(0.0f));
  EXPECT_NEAR(glm::length(at_centre), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(at_centre, glm::normalize(Vec3(1, 1, 1))), 0.0f, 1e-6f);
}

TEST(Torus, HitsFromOutside) {
  const auto side = subject([&] {
    return intersect_implicit(kTorus, Ray{Vec3(0, 0, -10), Vec3(0, 0, 1)}, Interval::positive());
  });
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 7.5f, 1e-5f);
  const auto top = subject([&] {
    return intersect_implicit(kTorus, Ray{Vec3(2, 5, 0), Vec3(0, -1, 0)}, Interval::positive());
  });
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->t, 4.5f, 1e-5f);
}

TEST(Torus, RayThroughTheHoleMisses) {
  EXPECT_FALSE(subject([&] {
    return intersect_implicit(kTorus, Ray{Vec3(0, 5, 0), Vec3(0, -1, 0)}, Interval::positive());
  }));
  EXPECT_FALSE(subject([&] {
    return intersect_implicit(kTorus, Ray{Vec3(-10, 3, 0), Vec3(1, 0, 0)}, Interval::positive());
  }));
}

TEST(Torus, HitsFromInsideTheTube) {
  const auto hit = subject([&] {
    return intersect_implicit(kTorus, Ray{Vec3(2, 0, 0), Vec3(0, 1, 0)}, Interval::positive());
  });
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 0.5f, 1e-5f);
}

TEST(Torus, NearestOfFourRootsAndTheRange) {
  // Along the x axis from x = -10 the ray crosses the surface at x = -2.5, -1.5, 1.5, 2.5.
  const Ray ray{Vec3(-10, 0, 0), Vec3(1, 0, 0)};
  const auto first = subject([&] { return intersect_implicit(kTorus, ray, Interval::positive()); });
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->t, 7.5f, 1e-5f);
  const auto third = subject([&] { return intersect_implicit(kTorus, ray, Interval{9.0f, kInfinity}); });
  ASSERT_TRUE(third);
  EXPECT_NEAR(third->t, 11.5f, 1e-5f);
  EXPECT_FALSE(subject([&] { return intersect_implicit(kTorus, ray, Interval{0.0f, 7.0f}); }));
}

// The torus's exact signed distance, in double.
double distance_double(const DVec3& p) {
  return std::hypot(std::hypot(p.x, p.z) - 2.0, p.y) - 0.5;
}

// Nearest root along the ray by a fine scan for a sign change and bisection, all in double.
// Returns -1 for a miss. `grazing` is set when, before that root, the distance along the ray has a
// local minimum within 2e-3 of zero: a near-tangent ray whose answer float cannot settle.
double reference_root(const Ray& ray, bool& grazing) {
  const DVec3 o(ray.origin), d(ray.direction);
  constexpr int kSteps = 40000;
  const double t_end = 30.0, dt = t_end / kSteps;
  double before = distance_double(o), previous = distance_double(o + dt * d);
  grazing = false;
  for (int i = 2; i <= kSteps; ++i) {
    const double t = dt * i;
    const double value = distance_double(o + t * d);
    if (previous < before && previous <= value && std::abs(previous) < 2e-3) grazing = true;
    if ((value < 0.0) != (previous < 0.0)) {
      double lo = t - dt, hi = t;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((distance_double(o + mid * d) < 0.0) == (previous < 0.0) ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    before = previous;
    previous = value;
  }
  return -1.0;
}

TEST(Torus, AgreesWithADoublePrecisionReferenceOnRandomRays) {
  Rng rng(99, 0, 0);
  int compared = 0;
  for (int i = 0; i < 2000; ++i) {
    // From a random point on a sphere of radius 8 towards a random point in the torus's box.
    const Vec3 from = 8.0f * glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
    const Vec3 to = Vec3(rng.uniform() * 5 - 2.5f, rng.uniform() - 0.5f, rng.uniform() * 5 - 2.5f);
    const Ray ray{from, glm::normalize(to - from)};
    bool grazing = false;
    const double expected = reference_root(ray, grazing);
    const auto hit = subject([&] { return intersect_implicit(kTorus, ray, Interval::positive()); });
    if (grazing) continue;  // tangent: too close to call in float
    ++compared;
    ASSERT_EQ(hit.has_value(), expected >= 0.0) << "ray " << i;
    if (hit) {
      // On the surface to 1e-5 scene units (4e-6 of the torus's size), measured in double...
      const DVec3 point = DVec3(ray.origin) + double(hit->t) * DVec3(ray.direction);
      EXPECT_LT(std::abs(distance_double(point)), 1e-5) << "ray " << i;
      // ...and on the NEAREST root, not a later crossing.
      EXPECT_NEAR(hit->t, expected, 1e-3) << "ray " << i;
    }
  }
  EXPECT_GT(compared, 1900);
}

TEST(Torus, TiltedAndMovedTorusGivesTheSameDistances) {
  // The same ray, rotated and moved with the torus, must hit at the same t.
  const Vec3 axis = glm::normalize(Vec3(1, 1, 0));
  const Vec3 centre(3, -2, 7);
  const TorusSurface tilted(Torus{centre, axis, 2.0f, 0.5f});
  // Rotation taking +y to axis: about z by -45 degrees. It takes +x to (1, -1, 0)/sqrt 2.
  const Vec3 x_axis = glm::normalize(Vec3(1, -1, 0));
  const Ray ray{centre - 10.0f * x_axis, x_axis};
  const auto hit = subject([&] { return intersect_implicit(tilted, ray, Interval::positive()); });
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 7.5f, 1e-5f);
}

TEST(Torus, ScaledTorusIsHitAtTheScaledDistance) {
  // The torus and the ray scaled by s: the hit scales with them. The tolerance must scale too:
  // at s = 1000 the coordinates' rounding (~1e-3) is far above a fixed 1e-5.
  for (const float s : {1e-3f, 1.0f, 1e3f}) {
    const TorusSurface scaled(Torus{Vec3(0), Vec3(0, 1, 0), 2.0f * s, 0.5f * s});
    const auto hit = subject([&] {
      return intersect_implicit(scaled, Ray{Vec3(-2.0f * s, 10.0f * s, 0), Vec3(0, -1, 0)}, Interval::positive());
    });
    ASSERT_TRUE(hit) << "scale " << s;
    EXPECT_NEAR(hit->t, 9.5f * s, 1e-5f * 9.5f * s) << "scale " << s;
  }
}

// The unit sphere's distance times 1.5: a bound that overestimates (not 1-Lipschitz), so a
// sphere-tracing step from outside lands inside, and intersect_implicit must bisect the bracket
// (its step 3) and polish the root within it. From 3.5 out it is flat (3.75, with gradient 0), so
// Newton's method started there, far from the root, goes nowhere.
class SteepSphere final : public ImplicitSurface {
 public:
  float distance(Vec3 p) const override { return 1.5f * std::min(glm::length(p) - 1.0f, 2.5f); }
  Vec3 gradient(Vec3 p) const override { return glm::length(p) < 3.5f ? 1.5f * glm::normalize(p) : Vec3(0); }
  Sphere bounding_sphere() const override { return Sphere{Vec3(0), 4.0f}; }
};

TEST(Torus, AnOverestimatingBoundIsBisectedToTheNearestRoot) {
  // From z = -10 towards the unit sphere, entering its bounding sphere at z = -4: the first step,
  // 3.75, lands at z = -0.25, inside. Offsets up to 0.4 from the axis keep that landing inside.
  const SteepSphere surface;
  for (const float offset : {0.0f, 0.15f, 0.3f, 0.4f}) {
    const Ray ray{Vec3(offset, 0.5f * offset, -10.0f), Vec3(0, 0, 1)};
    const float expected = 10.0f - std::sqrt(1.0f - 1.25f * offset * offset);
    const auto hit = subject([&] { return intersect_implicit(surface, ray, Interval::positive()); });
    ASSERT_TRUE(hit) << "offset " << offset;
    EXPECT_NEAR(hit->t, expected, 2e-5f) << "offset " << offset;
  }
}

// f = (1 - x)^3 / 6: the half-space x > 1 with a triple root at its face, where g' = 0 too, so
// Newton's method only crawls there (each step cuts the error by a third). From x = -2 the first
// step, 27/6 = 4.5, lands at x = 2.5, inside: only bisecting that bracket down to the tolerance
// finds the root; Newton's four polishing steps from the bracket's middle (0.75 away) would stop
// about 0.15 short of it.
class CubicWall final : public ImplicitSurface {
 public:
  float distance(Vec3 p) const override { return (1.0f - p.x) * (1.0f - p.x) * (1.0f - p.x) / 6.0f; }
  Vec3 gradient(Vec3 p) const override { return Vec3(-0.5f * (1.0f - p.x) * (1.0f - p.x), 0.0f, 0.0f); }
  Sphere bounding_sphere() const override { return Sphere{Vec3(1.0f, 0.0f, 0.0f), 3.0f}; }
};

TEST(Torus, ABracketIsBisectedWhereNewtonAloneWouldCrawl) {
  const CubicWall surface;
  const Ray ray{Vec3(-5.0f, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f)};  // enters the bound at x = -2, t = 3
  const auto hit = subject([&] { return intersect_implicit(surface, ray, Interval::positive()); });
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 6.0f, 1e-3f) << "the face x = 1";
}

// min(y, 1/64): a valid bound on the distance to the plane y = 0 whose every step above y = 1/64
// is exactly 1/64, so a ray straight down from y = n / 64 reaches the plane at step n exactly.
class StaircasePlane final : public ImplicitSurface {
 public:
  float distance(Vec3 p) const override { return std::min(p.y, kStep); }
  Vec3 gradient(Vec3) const override { return Vec3(0, 1, 0); }
  Sphere bounding_sphere() const override { return Sphere{Vec3(0), 16.0f}; }
  static constexpr float kStep = 1.0f / 64.0f;
};

TEST(Torus, TheMarchTakesAtMostItsBudgetOfSteps) {
  // Found at step n < kMaxSphereTracingSteps; at step n = kMaxSphereTracingSteps it is too late.
  const StaircasePlane plane;
  for (const int n : {1, 100, kMaxSphereTracingSteps - 1}) {
    const auto hit = subject([&] {
      return intersect_implicit(plane, Ray{Vec3(0, float(n) * StaircasePlane::kStep, 0), Vec3(0, -1, 0)},
                                Interval::positive());
    });
    ASSERT_TRUE(hit) << n << " steps";
    EXPECT_EQ(hit->steps, n);
    EXPECT_EQ(hit->t, float(n) * StaircasePlane::kStep);
  }
  EXPECT_FALSE(subject([&] {
    return intersect_implicit(plane,
                              Ray{Vec3(0, float(kMaxSphereTracingSteps) * StaircasePlane::kStep, 0), Vec3(0, -1, 0)},
                              Interval::positive());
  })) << "a root that needs kMaxSphereTracingSteps steps or more counts as a miss";
}

TEST(Torus, GrazingRaysTerminateWithoutNan) {
  // Rays skimming the top of the tube (y = r): sphere tracing slows down; it must still end.
  for (float dy : {0.0f, 1e-7f, 1e-4f, -1e-4f}) {
    const auto hit = subject([&] {
      return intersect_implicit(kTorus, Ray{Vec3(-10, 0.5f + dy, 0), glm::normalize(Vec3(1, 0, 0))},
                                Interval::positive());
    });
    if (hit) {
      EXPECT_TRUE(std::isfinite(hit->t));
      EXPECT_LE(hit->steps, kMaxSphereTracingSteps);
    }
  }
}

}  // namespace
}  // namespace rt
