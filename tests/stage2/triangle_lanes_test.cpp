// The watertight test with a triangle's corners in SIMD lanes (02-whitted/triangle_lanes.h) against
// the scalar watertight test it must equal bit for bit, and the crack test of its own.
#include "02-whitted/triangle_ray.h"
#include "experiments/triangle_leaks.h"
#include "stage2/aimed_rays.h"
#include "support/test_support.h"

#include "stage2/records.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::same_bits;
using testing::subject;

// Counts the cases where the two tests disagree (a hit against a miss, or any bit of t, b1, b2),
// and how many of the cases were hits, so that a test can insist on both kinds.
struct LaneAgreement {
  int cases = 0, hits = 0, disagreements = 0;

  void check(const Ray& ray, Vec3 v0, Vec3 v1, Vec3 v2, Interval range) {
    const auto [scalar, lanes] = subject([&] {
      const TriangleRay prepared(ray);
      return std::pair(intersect_triangle_watertight(prepared.watertight, v0, v1, v2, range),
                       intersect_triangle_lanes(prepared.watertight, prepared.lanes, TriangleCorners(v0, v1, v2), range));
    });
    ++cases;
    hits += scalar.has_value();
    const bool same = scalar.has_value() == lanes.has_value() &&
                      (!scalar || (same_bits(scalar->t, lanes->t) && same_bits(scalar->b1, lanes->b1) &&
                                   same_bits(scalar->b2, lanes->b2)));
    if (!same && disagreements++ < 5)
      ADD_FAILURE() << "ray (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") -> ("
                    << ray.direction.x << ", " << ray.direction.y << ", " << ray.direction.z << "): scalar "
                    << (scalar ? scalar->t : -1.0f) << ", lanes " << (lanes ? lanes->t : -1.0f);
  }
};

// Random triangles from 10^-3 to 10^3 in size, up to 10^3 away from the origin, and rays aimed at
// them (aimed_rays.h: zero direction components, short ranges, rays that start on the triangle).
TEST(TriangleLanes, AnswersAsTheWatertightTestBitForBit) {
  Rng rng(7, 0, 0);
  LaneAgreement agreement;
  for (int i = 0; i < 200000; ++i) {
    const float size = std::pow(10.0f, -3.0f + 6.0f * rng.uniform());
    const Vec3 centre = random_point(rng) * std::pow(10.0f, 3.0f * rng.uniform());
    const Vec3 v0 = centre + size * random_point(rng), v1 = centre + size * random_point(rng),
               v2 = centre + size * random_point(rng);
    if (const std::optional<AimedRay> aimed = aimed_ray(rng, i, v0, v1, v2, size))
      agreement.check(aimed->ray, v0, v1, v2, aimed->range);
  }
  EXPECT_EQ(agreement.disagreements, 0) << "of " << agreement.cases;
  EXPECT_GT(agreement.hits, agreement.cases / 10);  // both hits and misses were compared
  EXPECT_LT(agreement.hits, agreement.cases * 9 / 10);
}

// Rays through the corners and along the edges of triangles with small integer corners: there the
// float edge functions are exactly 0 and both tests recompute them in double, and a ray that runs
// in the triangle's plane (det = 0) must be refused by both.
TEST(TriangleLanes, AnswersAsTheWatertightTestOnEdgesAndCorners) {
  const Vec3 corners[][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                             {{0, 0, 0}, {2, 0, 1}, {0, 2, 2}},
                             {{-1, -1, 3}, {1, -1, 3}, {0, 1, 3}},
                             {{0, 0, 0}, {0, 4, 0}, {0, 0, 4}}};
  LaneAgreement agreement;
  for (const auto& v : corners)
    for (int a = 0; a < 3; ++a)
      for (int step = 0; step <= 4; ++step) {
        // A point on edge (a, a + 1), a quarter of the edge at a time (exact in binary).
        const Vec3 p = v[a] + float(step) * 0.25f * (v[(a + 1) % 3] - v[a]);
        for (const Vec3 d : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(1, 2, 3),
                             Vec3(-3, 1, -2), v[(a + 1) % 3] - v[a]}) {
          const Vec3 direction = glm::normalize(d);
          agreement.check(Ray{p - 5.0f * direction, direction}, v[0], v[1], v[2], Interval::positive());
        }
      }
  EXPECT_EQ(agreement.disagreements, 0) << "of " << agreement.cases;
  EXPECT_GT(agreement.hits, agreement.cases / 3);  // the rays in a triangle's plane miss
}

// The crack test of stage 2 (tests/experiments/triangle_leaks.h), with the lanes: rays aimed
// exactly at the shared edges and vertices of a closed, jittered mesh at four scales.
TEST(TriangleLanes, NoRayPassesThroughSharedEdges) {
  for (const float scale : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const LeakSetup setup = make_leak_setup(scale, 4, 2024);
    EXPECT_EQ(subject([&] { return count_leaks(setup.mesh, setup.edge_rays, TriangleMethod::watertight_lanes); }), 0) << "scale " << scale;
    EXPECT_EQ(subject([&] { return count_leaks(setup.mesh, setup.vertex_rays, TriangleMethod::watertight_lanes); }), 0) << "scale " << scale;
  }
}

}  // namespace
}  // namespace rt
