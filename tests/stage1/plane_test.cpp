#include "01-ray-casting/plane_intersection.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::subject;

const Plane kFloor{Vec3(0, -1, 0), Vec3(0, 1, 0)};

TEST(Plane, HitFromAbove) {
  const auto t = subject([&] {
    return intersect_plane(Ray{Vec3(0, 1, 0), glm::normalize(Vec3(1, -1, 0))}, kFloor, Interval::positive());
  });
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 2.0f * std::sqrt(2.0f), 1e-6f);
}

TEST(Plane, HitFromBelowTooPlanesAreTwoSided) {
  const auto t = subject([&] {
    return intersect_plane(Ray{Vec3(0, -3, 0), Vec3(0, 1, 0)}, kFloor, Interval::positive());
  });
  ASSERT_TRUE(t);
  EXPECT_FLOAT_EQ(*t, 2.0f);
}

TEST(Plane, BehindTheOriginIsNotHit) {
  EXPECT_FALSE(subject([&] {
    return intersect_plane(Ray{Vec3(0, 1, 0), Vec3(0, 1, 0)}, kFloor, Interval::positive());
  }));
}

TEST(Plane, ParallelRaysNeverHitAndNeverGiveNan) {
  EXPECT_FALSE(subject([&] {
    return intersect_plane(Ray{Vec3(0, 1, 0), Vec3(1, 0, 0)}, kFloor, Interval::positive());
  }));
  // Inside the plane: 0 / 0 would be NaN.
  EXPECT_FALSE(subject([&] {
    return intersect_plane(Ray{Vec3(0, -1, 0), Vec3(1, 0, 0)}, kFloor, Interval::positive());
  }));
  // -0 direction component: the division would give -inf.
  EXPECT_FALSE(subject([&] {
    return intersect_plane(Ray{Vec3(0, 1, 0), Vec3(1, -0.0f, 0)}, kFloor, Interval::positive());
  }));
}

TEST(Plane, GrazingRaysGiveFiniteDistances) {
  for (float dy : {-1e-3f, -1e-6f, -1e-20f, -1e-38f, -1e-45f}) {
    const auto t = subject([&] {
      return intersect_plane(Ray{Vec3(0, 0, 0), glm::normalize(Vec3(1, dy, 0))}, kFloor, Interval::positive());
    });
    if (t) {
      EXPECT_TRUE(std::isfinite(*t)) << dy;
    }
  }
}

TEST(Plane, TiltedPlaneThroughAPoint) {
  const Plane tilted{Vec3(1, 1, 1), glm::normalize(Vec3(1, 1, 1))};
  const auto t = subject([&] {
    return intersect_plane(Ray{Vec3(0), glm::normalize(Vec3(1, 1, 1))}, tilted, Interval::positive());
  });
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, std::sqrt(3.0f), 1e-6f);
}

}  // namespace
}  // namespace rt
