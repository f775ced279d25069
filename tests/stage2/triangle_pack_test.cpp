// Four triangles in the lanes of one register (02-whitted/triangle_pack.h) against the scalar
// watertight test, lane by lane: the pack's answer must be the nearest of the four scalar answers,
// bit for bit, with a tie going to the lowest lane.
#include "02-whitted/triangle_ray.h"
#include "experiments/triangle_leaks.h"
#include "stage2/aimed_rays.h"
#include "stage2/records.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <array>

namespace rt {
namespace {

using testing::same_bits;
using testing::subject;

using Corners = std::array<Vec3, 3>;

// What the pack must answer: the scalar test on each of the first `count` triangles in turn, the
// range shrinking at each hit (so a later triangle at the same t is not taken).
std::optional<PackHit> one_at_a_time(const TriangleRay& ray, const Corners* triangles, int count, Interval range) {
  std::optional<PackHit> nearest;
  for (int lane = 0; lane < count; ++lane)
    if (const auto hit = intersect_triangle_watertight(ray.watertight, triangles[lane][0], triangles[lane][1],
                                                       triangles[lane][2], range)) {
      nearest = PackHit{hit->t, hit->b1, hit->b2, lane};
      range.max = hit->t;
    }
  return nearest;
}

TrianglePack pack_of(const Corners* triangles, int count) {
  std::array<TriangleCorners, TrianglePack::kLanes> corners;
  for (int i = 0; i < count; ++i) corners[size_t(i)] = TriangleCorners(triangles[i][0], triangles[i][1], triangles[i][2]);
  return TrianglePack(std::span<const TriangleCorners>(corners.data(), size_t(count)));
}

// Counts disagreements (hit against miss, another lane, or any bit of t, b1, b2) and hits; check
// returns the pack's answer.
struct PackAgreement {
  int cases = 0, hits = 0, disagreements = 0;

  std::optional<PackHit> check(const Ray& ray, const Corners* triangles, int count, Interval range) {
    const auto [expected, pack] = subject([&] {
      const TriangleRay prepared(ray);
      return std::pair(one_at_a_time(prepared, triangles, count, range),
                       intersect_triangle_pack(prepared.watertight, prepared.lanes, pack_of(triangles, count), range));
    });
    ++cases;
    hits += expected.has_value();
    const bool same = expected.has_value() == pack.has_value() &&
                      (!expected || (expected->lane == pack->lane && same_bits(expected->t, pack->t) &&
                                     same_bits(expected->b1, pack->b1) && same_bits(expected->b2, pack->b2)));
    if (!same && disagreements++ < 5)
      ADD_FAILURE() << "case " << cases << ", " << count << " triangles: one at a time "
                    << (expected ? std::to_string(expected->t) + " in lane " + std::to_string(expected->lane) : "miss")
                    << ", pack " << (pack ? std::to_string(pack->t) + " in lane " + std::to_string(pack->lane) : "miss");
    return pack;
  }
};

// Packs of one to four random triangles near each other (sizes 10^-3 to 10^3, up to 10^3 from the
// origin), and rays aimed at one of them (aimed_rays.h: zero direction components, short ranges,
// rays that start on the triangle).
TEST(TrianglePack, AnswersAsTheWatertightTestLaneByLane) {
  Rng rng(11, 0, 0);
  PackAgreement agreement;
  for (int i = 0; i < 100000; ++i) {
    const int count = 1 + i % 4;
    const float size = std::pow(10.0f, -3.0f + 6.0f * rng.uniform());
    const Vec3 centre = random_point(rng) * std::pow(10.0f, 3.0f * rng.uniform());
    Corners triangles[4];
    for (int k = 0; k < count; ++k)
      for (Vec3& v : triangles[k]) v = centre + size * random_point(rng);
    const Corners& t = triangles[int(rng.uniform() * float(count)) % count];
    if (const std::optional<AimedRay> aimed = aimed_ray(rng, i, t[0], t[1], t[2], size))
      agreement.check(aimed->ray, triangles, count, aimed->range);
  }
  EXPECT_EQ(agreement.disagreements, 0) << "of " << agreement.cases;
  EXPECT_GT(agreement.hits, agreement.cases / 10);  // both hits and misses were compared
  EXPECT_LT(agreement.hits, agreement.cases * 9 / 10);
}

// A fan of four triangles around a vertex, a tent over the square |x| + |y| <= 2, with small
// integer corners: rays through the shared vertex and along the shared edges, where the float edge
// functions are exactly 0. Each ray is answered by the lowest lane whose triangle holds the point,
// and a vertical ray through a point of the tent (a height field) hits it: none slips between.
TEST(TrianglePack, AnswersOnSharedEdgesAndTheSharedVertex) {
  const Vec3 apex(0, 0, 1), rim[4] = {{2, 0, 0}, {0, 2, 0}, {-2, 0, 0}, {0, -2, 0}};
  Corners fan[4];
  for (int k = 0; k < 4; ++k) fan[k] = {apex, rim[k], rim[(k + 1) % 4]};
  PackAgreement agreement;
  int vertical = 0, vertical_hits = 0;
  for (int k = 0; k < 4; ++k)
    for (int step = 0; step <= 4; ++step) {
      const Vec3 p = apex + float(step) * 0.25f * (rim[k] - apex);  // on the edge shared by k - 1 and k
      for (const Vec3 d : {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1, 2, -3), Vec3(-3, 1, -2), Vec3(1, 0, 0)}) {
        const Vec3 direction = glm::normalize(d);
        const Ray ray{p - 5.0f * direction, direction};
        const bool hit = agreement.check(ray, fan, 4, Interval::positive()).has_value();
        if (d.x != 0.0f || d.y != 0.0f) continue;
        ++vertical;
        vertical_hits += hit;
      }
    }
  EXPECT_EQ(agreement.disagreements, 0) << "of " << agreement.cases;
  EXPECT_EQ(vertical_hits, vertical);
}

// Stage 2's crack test (tests/experiments/triangle_leaks.h), with the mesh's triangles four at a
// time: rays aimed exactly at the shared edges and vertices of a closed, jittered mesh, at four
// scales. There the float edge functions round to exactly 0 where the true ones are not, and only
// the recomputation in double gives the scalar test's answers (and lets no ray through).
TEST(TrianglePack, AnswersOnTheEdgesOfAClosedMeshAndLetsNoRayThrough) {
  for (const float scale : {1e-3f, 1.0f, 1e3f, 1e5f}) {
    const LeakSetup setup = make_leak_setup(scale, 4, 2024);
    std::vector<Corners> triangles;
    for (const auto& c : setup.mesh.triangles)
      triangles.push_back({setup.mesh.positions[c[0]], setup.mesh.positions[c[1]], setup.mesh.positions[c[2]]});
    PackAgreement agreement;
    int leaks = 0;
    for (const auto* rays : {&setup.edge_rays, &setup.vertex_rays})
      for (const Ray& ray : *rays) {
        bool hit = false;
        for (size_t first = 0; first < triangles.size(); first += 4) {
          const int count = int(std::min<size_t>(4, triangles.size() - first));
          hit = agreement.check(ray, &triangles[first], count, Interval::positive()).has_value() || hit;
        }
        leaks += !hit;
      }
    EXPECT_EQ(agreement.disagreements, 0) << "scale " << scale << ", of " << agreement.cases;
    EXPECT_EQ(leaks, 0) << "scale " << scale;
  }
}

// Two copies of one triangle in lanes 1 and 3 (and others elsewhere): equal t, and the pack names
// lane 1, as testing one lane after another with a shrinking range would. A pack of fewer than four
// repeats its first triangle, which must never be named instead of it.
TEST(TrianglePack, ATieGoesToTheLowestLane) {
  const Corners far{{{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}}};
  const Corners near{{{-1, -1, 2}, {1, -1, 2}, {0, 1, 2}}};
  const Corners aside{{{10, 10, 1}, {11, 10, 1}, {10, 11, 1}}};
  const Ray ray{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  const Corners twins[4] = {far, near, aside, near};
  const auto pack = [&](const Corners* triangles, int count, Interval range) {
    return subject([&] {
      const TriangleRay prepared(ray);
      return intersect_triangle_pack(prepared.watertight, prepared.lanes, pack_of(triangles, count), range);
    });
  };
  const auto hit = pack(twins, 4, Interval::positive());
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->lane, 1);
  EXPECT_EQ(hit->t, 2.0f);
  const Corners two[2] = {near, far};
  const auto partial = pack(two, 2, Interval::positive());
  ASSERT_TRUE(partial.has_value());
  EXPECT_EQ(partial->lane, 0);
  // A range that ends before the nearest hit leaves the next one; one that ends at it, none nearer.
  const auto beyond = pack(twins, 4, Interval{2.0f, 10.0f});
  ASSERT_TRUE(beyond.has_value());
  EXPECT_EQ(beyond->lane, 0);
  EXPECT_FALSE(pack(twins, 4, Interval{0.0f, 2.0f}));
}

}  // namespace
}  // namespace rt
