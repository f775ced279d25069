#include "02-whitted/triangle_ray.h"
#include "experiments/triangle_leaks.h"
#include "common/random.h"

#include "stage2/records.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::subject;

struct TriangleTest {
  const char* name;
  TriangleMethod method;
};
void PrintTo(const TriangleTest& t, std::ostream* out) { *out << t.name; }

// Both tests must pass every exact case; only the crack test below tells them apart.
class BothTriangleTests : public ::testing::TestWithParam<TriangleTest> {
 protected:
  std::optional<TriangleHit> hit(const Ray& ray, Vec3 v0, Vec3 v1, Vec3 v2,
                                 Interval range = Interval::positive()) const {
    return subject([&] { return intersect_triangle(GetParam().method, ray, v0, v1, v2, range); });
  }
  std::optional<TriangleHit> hit(const Ray& ray, Interval range = Interval::positive()) const {
    return hit(ray, kV0, kV1, kV2, range);
  }
  // The triangle (0,0,2) (1,0,2) (0,1,2), facing -z (towards the origin).
  const Vec3 kV0{0, 0, 2}, kV1{1, 0, 2}, kV2{0, 1, 2};
};

// A ray along +z through the point (x, y) of the triangle's plane.
Ray through(float x, float y) { return Ray{Vec3(x, y, 0), Vec3(0, 0, 1)}; }

TEST_P(BothTriangleTests, HitInsideGivesDistanceAndBarycentrics) {
  const auto h = hit(through(0.25f, 0.5f));
  ASSERT_TRUE(h);
  EXPECT_FLOAT_EQ(h->t, 2.0f);
  EXPECT_FLOAT_EQ(h->b1, 0.25f);  // weight of v1 = (1, 0): the x coordinate
  EXPECT_FLOAT_EQ(h->b2, 0.5f);   // weight of v2 = (0, 1): the y coordinate
}

TEST_P(BothTriangleTests, SlantedRayHitsWhereTheLineMeetsThePlane) {
  const Vec3 target(0.2f, 0.3f, 2.0f), origin(-1.0f, 2.0f, -1.0f);
  const auto h = hit(Ray{origin, glm::normalize(target - origin)});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->t, glm::length(target - origin), 1e-5f);
  EXPECT_NEAR(h->b1, 0.2f, 1e-6f);
  EXPECT_NEAR(h->b2, 0.3f, 1e-6f);
}

TEST_P(BothTriangleTests, EdgesAndVerticesCountAsInside) {
  // Exactly representable points on each edge and at each vertex, ray along the axis.
  for (const Vec2 p : {Vec2(0.5f, 0.0f), Vec2(0.0f, 0.5f), Vec2(0.5f, 0.5f), Vec2(0.25f, 0.75f),
                       Vec2(0.0f, 0.0f), Vec2(1.0f, 0.0f), Vec2(0.0f, 1.0f)}) {
    EXPECT_TRUE(hit(through(p.x, p.y))) << "point (" << p.x << ", " << p.y << ")";
  }
}

TEST_P(BothTriangleTests, PointsOutsideAreMissed) {
  for (const Vec2 p : {Vec2(-0.01f, 0.5f), Vec2(0.5f, -0.01f), Vec2(0.51f, 0.5f), Vec2(1.0f, 1.0f),
                       Vec2(2.0f, -1.0f), Vec2(-5.0f, -5.0f)}) {
    EXPECT_FALSE(hit(through(p.x, p.y))) << "point (" << p.x << ", " << p.y << ")";
  }
}

TEST_P(BothTriangleTests, RaysParallelToThePlaneNeverHit) {
  // Off the plane, and lying exactly in it (0/0 territory for the textbook formulas).
  EXPECT_FALSE(hit(Ray{Vec3(-1, 0.25f, 1), Vec3(1, 0, 0)}));
  EXPECT_FALSE(hit(Ray{Vec3(-1, 0.25f, 2), Vec3(1, 0, 0)}));
  EXPECT_FALSE(hit(Ray{Vec3(0.2f, -1, 2), Vec3(0, 1, 0)}));
}

TEST_P(BothTriangleTests, BackFacesAreHitToo) {
  const auto front = hit(Ray{Vec3(0.25f, 0.25f, 0), Vec3(0, 0, 1)});
  const auto back = hit(Ray{Vec3(0.25f, 0.25f, 4), Vec3(0, 0, -1)});
  ASSERT_TRUE(front);
  ASSERT_TRUE(back);
  EXPECT_FLOAT_EQ(back->t, 2.0f);
  EXPECT_FLOAT_EQ(back->b1, front->b1);
  EXPECT_FLOAT_EQ(back->b2, front->b2);
}

TEST_P(BothTriangleTests, OnlyHitsInsideTheOpenRange) {
  EXPECT_FALSE(hit(Ray{Vec3(0.25f, 0.25f, 3), Vec3(0, 0, 1)})) << "triangle behind the origin";
  EXPECT_FALSE(hit(through(0.25f, 0.25f), Interval{0.0f, 1.5f})) << "beyond t_max";
  EXPECT_FALSE(hit(through(0.25f, 0.25f), Interval{0.0f, 2.0f})) << "t = t_max is outside";
  EXPECT_TRUE(hit(through(0.25f, 0.25f), Interval{1.0f, 2.5f}));
}

TEST_P(BothTriangleTests, TinyAndHugeTrianglesAreHit) {
  // No absolute epsilon: det scales with the area, so a fixed threshold would drop small triangles.
  for (const float s : {1e-6f, 1e-3f, 1e3f, 1e6f}) {
    const auto h = hit(Ray{Vec3(0.25f * s, 0.25f * s, -s), Vec3(0, 0, 1)}, s * kV0, s * kV1, s * kV2);
    ASSERT_TRUE(h) << "scale " << s;
    EXPECT_NEAR(h->t, 3.0f * s, 1e-6f * s);
  }
}

TEST_P(BothTriangleTests, DegenerateTrianglesNeverHitAndNeverGiveNan) {
  const std::vector<std::array<Vec3, 3>> degenerate = {
      {Vec3(0, 0, 2), Vec3(0, 0, 2), Vec3(0, 1, 2)},           // two equal vertices
      {Vec3(0, 0, 2), Vec3(1, 1, 2), Vec3(2, 2, 2)},           // collinear
      {Vec3(0.3f, 0.3f, 2), Vec3(0.3f, 0.3f, 2), Vec3(0.3f, 0.3f, 2)},  // a point
      {Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0.5f, 1e-30f, 2)},  // area 5e-31, all but flat
  };
  Rng rng(11, 0, 0);
  for (const auto& v : degenerate)
    for (int i = 0; i < 10000; ++i) {
      // Rays from around the origin aimed at the triangle's neighbourhood, including its line.
      const Vec3 target(rng.uniform() * 2.0f - 0.5f, i % 2 ? rng.uniform() * 2.0f - 0.5f : 0.0f, 2.0f);
      const Vec3 origin(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.0f);
      const auto h = hit(Ray{origin, glm::normalize(target - origin)}, v[0], v[1], v[2]);
      if (h) {
        // Only the nearly flat triangle has an area; it may be hit, but with finite numbers.
        ASSERT_EQ(v[2].y, 1e-30f) << "a zero-area triangle was hit";
        ASSERT_TRUE(std::isfinite(h->t) && std::isfinite(h->b1) && std::isfinite(h->b2));
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Triangle, BothTriangleTests,
                         ::testing::Values(TriangleTest{"moller_trumbore", TriangleMethod::moller_trumbore},
                                           TriangleTest{"watertight", TriangleMethod::watertight}),
                         [](const auto& info) { return std::string(info.param.name); });

// The watertight test's bound on the rounding error of t (watertight_t_error_bound) must cover
// that error: a ray that starts exactly on a triangle has t = 0, so any t the test computes is
// rounding noise, and it must never count as a hit, at any angle, grazing ones included. And the
// bound must not be absurdly loose: from 10^-3 of the triangle's size above it, the triangle is
// hit. The corners are multiples of 64 (times a power of two, from 2^-10 to 2^10) and the origin
// is v0 + w (v1 - v0) + w (v2 - v0) with w = 1/4 or 1/64: every coordinate exact in float, the
// origin exactly on the triangle, inside it.
TEST(WatertightBound, RaysFromOnATriangleNeverHitItAndRaysFromJustAboveDo) {
  Rng rng(404, 0, 0);
  const auto corner = [&rng](float scale) {
    return scale * 64.0f * Vec3(std::floor(rng.uniform() * 2001.0f) - 1000.0f, std::floor(rng.uniform() * 2001.0f) - 1000.0f,
                               std::floor(rng.uniform() * 2001.0f) - 1000.0f);
  };
  int self_hits = 0, rays = 0, near_misses = 0, well_shaped = 0;
  for (int i = 0; i < 3000; ++i) {
    const float scale = std::ldexp(1.0f, int(rng.uniform() * 21.0f) - 10);
    const Vec3 v0 = corner(scale), v1 = corner(scale), v2 = corner(scale);
    // Near the middle, or near the corner v0, where the corners' sheared coordinates differ most.
    const float w = i % 2 == 0 ? 0.25f : 1.0f / 64.0f;
    const Vec3 on = v0 + w * (v1 - v0) + w * (v2 - v0);
    const Vec3 cross = glm::cross(v1 - v0, v2 - v0);
    if (glm::length(cross) == 0.0f) continue;
    const Vec3 normal = glm::normalize(cross);
    for (int k = 0; k < 4; ++k) {  // directions of every angle: a quarter of them grazing
      Vec3 d = glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
      if (k == 0) d = glm::normalize(d - glm::dot(d, normal) * normal + 1e-3f * normal);
      ++rays;
      self_hits += subject([&] { return intersect_triangle_watertight(Ray{on, d}, v0, v1, v2, Interval::positive()); }).has_value();
    }
    // Well shaped (area at least a tenth of the longest edge squared): from just above, a hit.
    const float longest = std::max({glm::length(v1 - v0), glm::length(v2 - v1), glm::length(v0 - v2)});
    if (0.5f * glm::length(cross) < 0.1f * longest * longest) continue;
    ++well_shaped;
    const Vec3 above = on + 1e-3f * longest * normal;
    near_misses += !subject([&] { return intersect_triangle_watertight(Ray{above, -normal}, v0, v1, v2, Interval::positive()); });
    near_misses += !subject([&] { return intersect_triangle_watertight(Ray{on - 1e-3f * longest * normal, normal}, v0, v1, v2,
                                                  Interval::positive()); });
  }
  EXPECT_EQ(self_hits, 0) << "of " << rays << " rays that start on a triangle";
  EXPECT_GT(well_shaped, 1000);
  EXPECT_EQ(near_misses, 0) << "of " << 2 * well_shaped << " rays from 1e-3 of its size above or below it";
}

// The refusal rule in the header: a hit is refused exactly when its t is not above
// watertight_t_error_bound of the largest moduli of the corners' sheared coordinates and edge
// functions. The test recomputes those moduli in double (the bound is symmetric in x' and y', so
// the axes' order does not matter) and checks both sides of the rule: t below 0.8 of the bound is
// refused, t above 1.25 of it is hit. (Measured over 40,000 rays of the three kinds below, the
// float t moves the switch by at most 2.7 % of the bound: the margins are 8 times the rounding.)
// The rays start where building the bound from the wrong moduli moves it most:
// - near a corner, whose sheared x' and y' are then nearly 0 (the smallest moduli would be 0);
// - near the middle of an edge, where that edge's function is nearly 0;
// - near the middle of the long side of a right isosceles triangle seen almost face on, with its
//   sides at 45 degrees to the axes: there the edge functions reach 2 max_x max_y, their largest
//   share of the bound (a third).
TEST(WatertightBound, TheRefusalThresholdIsTheBoundOfTheShearedCorners) {
  Rng rng(1919, 0, 0);
  const auto point = [&rng] { return Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f; };
  int refused = 0, hit = 0;
  for (int i = 0; i < 12000; ++i) {
    Vec3 v0 = point(), v1 = point(), v2 = point(), d = glm::normalize(point());
    float w1 = 1.0f / 64.0f, w2 = 1.0f / 64.0f;  // on = v0 + w1 (v1 - v0) + w2 (v2 - v0)
    if (i % 3 == 1) w1 = 0.5f, w2 = 1.0f / 1024.0f;
    if (i % 3 == 2) {
      const Vec3 middle = point(), tilt(0.5f, 0.25f, 0.0f);  // the plane z = middle.z + tilt.(p - middle)
      const float side = std::ldexp(1.0f, int(rng.uniform() * 8.0f) - 4);
      const auto in_plane = [&](float x, float y) { return middle + Vec3(x, y, tilt.x * x + tilt.y * y); };
      v0 = in_plane(-side, side), v1 = in_plane(side, -side), v2 = in_plane(side, side);
      d = glm::normalize(Vec3(0.1f * point().x, 0.1f * point().y, 1.0f));
      w1 = 0.5f, w2 = 1.0f / 1024.0f;
    }
    const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(v1 - v0), glm::dvec3(v2 - v0)));
    if (std::abs(glm::dot(glm::dvec3(d), normal)) < 0.3) continue;  // not grazing: t is well conditioned
    const Vec3 on = v0 + w1 * (v1 - v0) + w2 * (v2 - v0);
    const auto bound_from = [&](Vec3 origin) {
      const glm::dvec3 ray(d), a = glm::dvec3(v0 - origin), b = glm::dvec3(v1 - origin), c = glm::dvec3(v2 - origin);
      const glm::dvec3 m = glm::abs(ray);
      const int kz = m.x > m.y && m.x > m.z ? 0 : m.y > m.z ? 1 : 2, kx = (kz + 1) % 3, ky = (kz + 2) % 3;
      const auto sheared = [&](glm::dvec3 p) {
        return glm::dvec3(p[kx] - ray[kx] / ray[kz] * p[kz], p[ky] - ray[ky] / ray[kz] * p[kz], p[kz] / ray[kz]);
      };
      const glm::dvec3 sa = sheared(a), sb = sheared(b), sc = sheared(c);
      const double u = sc.x * sb.y - sc.y * sb.x, v = sa.x * sc.y - sa.y * sc.x, w = sb.x * sa.y - sb.y * sa.x;
      const auto largest = [](double p, double q, double r) { return float(std::max({std::abs(p), std::abs(q), std::abs(r)})); };
      return double(watertight_t_error_bound(largest(sa.x, sb.x, sc.x), largest(sa.y, sb.y, sc.y), largest(sa.z, sb.z, sc.z),
                                             largest(u, v, w), float(1.0 / (u + v + w))));
    };
    const double factor = i % 2 == 0 ? 0.7 : 1.4;
    const Vec3 origin = on - float(factor * bound_from(on)) * d;
    // The true t from the origin as rounded, and the bound the rule uses for it.
    const double t = glm::dot(glm::dvec3(v0) - glm::dvec3(origin), normal) / glm::dot(glm::dvec3(d), normal);
    const double bound = bound_from(origin);
    const bool reported = subject([&] { return intersect_triangle_watertight(Ray{origin, d}, v0, v1, v2, Interval::positive()); }).has_value();
    if (t < 0.8 * bound) {
      ++refused;
      EXPECT_FALSE(reported) << "ray " << i << ": t = " << t << " is below 0.8 of its error bound " << bound;
    } else if (t > 1.25 * bound) {
      ++hit;
      EXPECT_TRUE(reported) << "ray " << i << ": t = " << t << " is above 1.25 times its error bound " << bound;
    }
  }
  EXPECT_GT(refused, 3000);
  EXPECT_GT(hit, 3000);
}

// The crack test (stages/experiments/triangle_leaks.h): rays from inside a closed, jittered mesh
// aimed exactly at its shared edges and vertices, at four scales. 3,168 edge rays and 266 vertex
// rays per scale.
class Watertight : public ::testing::TestWithParam<float> {};

TEST_P(Watertight, NoRayPassesThroughTheWatertightTest) {
  const LeakSetup setup = make_leak_setup(GetParam(), 4, 2024);
  EXPECT_EQ(subject([&] { return count_leaks(setup.mesh, setup.edge_rays, TriangleMethod::watertight); }), 0);
  EXPECT_EQ(subject([&] { return count_leaks(setup.mesh, setup.vertex_rays, TriangleMethod::watertight); }), 0);
}

// Moeller-Trumbore leaks; the test pins the count measured when this was written (docs/stage2.md
// has the table) so that a change which makes it leak more is noticed: about 8% of the edge rays
// and 7% of the vertex rays (4 rays per edge, seed 2024).
struct MeasuredLeaks {
  float scale;
  int edge, vertex;
};
constexpr MeasuredLeaks kMollerTrumboreLeaks[] = {{1e-3f, 260, 24}, {1.0f, 250, 18}, {1e3f, 259, 21}, {1e5f, 265, 19}};

TEST_P(Watertight, MollerTrumboreLeaksNoMoreThanMeasured) {
  const LeakSetup setup = make_leak_setup(GetParam(), 4, 2024);
  const int edge = subject([&] { return count_leaks(setup.mesh, setup.edge_rays, TriangleMethod::moller_trumbore); });
  const int vertex = subject([&] { return count_leaks(setup.mesh, setup.vertex_rays, TriangleMethod::moller_trumbore); });
  for (const MeasuredLeaks& m : kMollerTrumboreLeaks)
    if (m.scale == GetParam()) {
      EXPECT_LE(edge, m.edge);
      EXPECT_LE(vertex, m.vertex);
    }
  std::printf("Moller-Trumbore at scale %g: %d of %zu edge rays and %d of %zu vertex rays leaked\n",
              double(GetParam()), edge, setup.edge_rays.size(), vertex, setup.vertex_rays.size());
}

INSTANTIATE_TEST_SUITE_P(Scales, Watertight, ::testing::Values(1e-3f, 1.0f, 1e3f, 1e5f),
                         [](const auto& info) {
                           const int exponent = int(std::lround(std::log10(info.param)));
                           return "scale_1e" + std::string(exponent < 0 ? "m" : "") + std::to_string(std::abs(exponent));
                         });

}  // namespace
}  // namespace rt
