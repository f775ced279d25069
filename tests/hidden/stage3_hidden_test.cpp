// Hidden tests of stage 3: the slab test on random boxes against clipping in double precision, and
// every BVH builder on a random triangle soup against the naive aggregate.
#include "stage3/bvh_test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::subject;

TEST(HiddenSlab, RandomBoxesAgreeWithDoubleClipping) {
  Rng rng(8675309, 0, 0);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Aabb box;
    box.expand(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - 2.0f);
    box.expand(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - 2.0f);
    // Aimed at a point of the box grown by 60%: about half the rays hit.
    const Vec3 origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 10.0f - 5.0f;
    const Vec3 target = box.centroid() + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5f) * 1.6f * box.extent();
    const Ray ray{origin, glm::normalize(target - origin)};
    double enter = 0.0, exit = 1e30;
    for (int axis = 0; axis < 3; ++axis) {
      const double o = ray.origin[axis], d = ray.direction[axis];
      double t0 = (box.lo[axis] - o) / d, t1 = (box.hi[axis] - o) / d;
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      exit = std::min(exit, t1);
    }
    // Decide only where double precision is clear of the boundary by a margin.
    if (std::abs(exit - enter) < 1e-4) continue;
    const std::optional<float> got = subject([&] { return intersect_aabb(box, RayInverse(ray), Interval{0.0f, 1e30f}); });
    ASSERT_EQ(got.has_value(), enter < exit) << "ray " << i;
    if (got) {
      EXPECT_NEAR(*got, enter, 1e-4 * (1.0 + enter)) << "ray " << i;
    }
    hits += got ? 1 : 0;
  }
  EXPECT_GT(hits, 5000);
}

// 3,000 random triangles of random sizes: long slivers and overlaps that no visible test uses.
std::shared_ptr<Primitives> random_soup() {
  Rng rng(1234567, 0, 0);
  TriangleMesh mesh;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 centre = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 10.0f - 5.0f;
    const float size = 0.05f + (i % 7 == 0 ? 3.0f : 0.4f) * rng.uniform();
    for (int k = 0; k < 3; ++k)
      mesh.positions.push_back(centre + size * (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f));
    mesh.triangles.push_back({std::uint32_t(3 * i), std::uint32_t(3 * i + 1), std::uint32_t(3 * i + 2)});
  }
  return primitives_of({std::move(mesh)}, {Sphere{Vec3(1, 1, 1), 0.7f}});
}

TEST(HiddenBvh, EveryBuilderAgreesWithNaiveOnARandomSoup) {
  const auto soup = random_soup();
  const std::vector<Ray> rays = random_rays(*soup, 4000, 99);
  expect_builders_agree_with_naive(soup, rays);
  // Every seventh ray: occluded by the naive aggregate, then by each builder's tree.
  const auto occluded = subject([&] {
    std::vector<std::vector<bool>> each(1);
    const NaiveAggregate naive(soup);
    for (size_t i = 0; i < rays.size(); i += 7) each[0].push_back(naive.occluded(rays[i], Interval::positive()));
    for (const Builder& builder : kBuilders) {
      const BvhAggregate bvh(soup, builder.options());
      each.emplace_back();
      for (size_t i = 0; i < rays.size(); i += 7) each.back().push_back(bvh.occluded(rays[i], Interval::positive()));
    }
    return each;
  });
  ASSERT_EQ(occluded.size(), std::size(kBuilders) + 1);
  for (size_t b = 0; b < std::size(kBuilders); ++b) {
    ASSERT_EQ(occluded[b + 1].size(), occluded[0].size());
    for (size_t k = 0; k < occluded[0].size(); ++k)
      EXPECT_EQ(occluded[b + 1][k], occluded[0][k]) << kBuilders[b].name << ", ray " << 7 * k;
  }
}

}  // namespace
}  // namespace rt
