#include "03-acceleration/aabb.h"
#include "common/random.h"
#include "support/subject.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

const Aabb kUnitBox{Vec3(0), Vec3(1)};

std::optional<float> slab(const Aabb& box, Vec3 origin, Vec3 direction, Interval range = Interval::positive()) {
  return testing::subject([&] { return intersect_aabb(box, RayInverse(Ray{origin, direction}), range); });
}

// The convention: boundaries count (a ray grazing a face or crossing a flat box hits), since a
// false hit only costs time while a false miss loses geometry.
TEST(Slab, TruthTableForZeroDirectionComponents) {
  EXPECT_TRUE(slab(kUnitBox, Vec3(-1, 0.5f, 0.5f), Vec3(1, +0.0f, 0))) << "d_y = +0 inside the y slab";
  EXPECT_TRUE(slab(kUnitBox, Vec3(-1, 0.5f, 0.5f), Vec3(1, -0.0f, -0.0f))) << "d_y = -0 inside the y slab";
  EXPECT_FALSE(slab(kUnitBox, Vec3(-1, 2.0f, 0.5f), Vec3(1, +0.0f, 0))) << "d_y = +0 outside the y slab";
  EXPECT_FALSE(slab(kUnitBox, Vec3(-1, -1.0f, 0.5f), Vec3(1, -0.0f, 0))) << "d_y = -0 outside the y slab";
  EXPECT_TRUE(slab(kUnitBox, Vec3(-1, 1.0f, 0.5f), Vec3(1, +0.0f, 0))) << "origin on the plane y = 1 (0 * inf = NaN)";
  EXPECT_TRUE(slab(kUnitBox, Vec3(-1, 0.0f, 0.5f), Vec3(1, -0.0f, 0))) << "origin on y = 0 with d_y = -0";
  EXPECT_TRUE(slab(kUnitBox, Vec3(0, 0, -1), Vec3(0, 0, 1))) << "origin on an edge (x = y = 0), along z";
  EXPECT_TRUE(slab(kUnitBox, Vec3(0.5f, 0.5f, -1), Vec3(-0.0f, -0.0f, 1)));
  EXPECT_TRUE(slab(kUnitBox, Vec3(0.5f, 0.5f, 2), Vec3(-0.0f, -0.0f, -1)));
}

TEST(Slab, EntryDistanceInsideBehindAndBeyond) {
  const auto t = slab(kUnitBox, Vec3(-2, 0.5f, 0.5f), Vec3(1, 0, 0));
  ASSERT_TRUE(t);
  EXPECT_FLOAT_EQ(*t, 2.0f);
  const auto inside = slab(kUnitBox, Vec3(0.5f), glm::normalize(Vec3(1, 2, 3)));
  ASSERT_TRUE(inside) << "a ray starting inside the box";
  EXPECT_EQ(*inside, 0.0f) << "the entry is clamped to range.min";
  EXPECT_FALSE(slab(kUnitBox, Vec3(2, 0.5f, 0.5f), Vec3(1, 0, 0))) << "box behind the ray";
  EXPECT_FALSE(slab(kUnitBox, Vec3(-2, 0.5f, 0.5f), Vec3(1, 0, 0), Interval{0.0f, 1.5f})) << "t_max before the entry";
  EXPECT_TRUE(slab(kUnitBox, Vec3(-2, 0.5f, 0.5f), Vec3(1, 0, 0), Interval{0.0f, 2.0f})) << "t_max at the entry";
  EXPECT_FALSE(slab(kUnitBox, Vec3(-2, 0.5f, 0.5f), Vec3(1, 0, 0), Interval{3.5f, kInfinity})) << "t_min past the exit";
  EXPECT_FALSE(slab(Aabb{}, Vec3(0), Vec3(0, 0, 1))) << "the empty box";
}

TEST(Slab, FlatBoxesAreHit) {
  // Zero thickness in z, at several depths: t_enter == t_exit, which only an inclusive test accepts.
  Rng rng(3, 0, 0);
  for (const float z : {0.0f, 0.1f, 7.3f, 1000.3f}) {
    const Aabb flat{Vec3(-1, -1, z), Vec3(1, 1, z)};
    for (int i = 0; i < 1000; ++i) {
      const Vec3 target(rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, z);
      const Vec3 origin(rng.uniform() - 0.5f, rng.uniform() - 0.5f, z - 5.0f);
      EXPECT_TRUE(slab(flat, origin, glm::normalize(target - origin))) << "z " << z << ", ray " << i;
    }
  }
}

// The reference: the same slab test in double on the same float ray, with no rounding margin.
// A box the reference says the ray crosses by more than a hair must be hit; one it misses by more
// than a hair must be missed; and nothing may come out NaN.
TEST(Slab, AgreesWithADoubleReferenceAndIsConservative) {
  Rng rng(4, 0, 0);
  int false_misses = 0, false_hits = 0, checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 c = (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * 100.0f;
    const Vec3 half = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * (i % 3 == 0 ? 1e-3f : 2.0f);
    const Aabb box{c - half, c + half};
    const Vec3 origin = (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * 1000.0f;
    // Aim near the box, sometimes exactly axis-aligned.
    Vec3 target = c + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * half * 1.5f;
    if (i % 5 == 0) target = Vec3(target.x, origin.y, origin.z);
    const Vec3 d = glm::normalize(target - origin);
    double t0 = 0.0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0f) {
        if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) t1 = -1.0;
        continue;
      }
      double tn = (double(box.lo[a]) - origin[a]) / d[a], tf = (double(box.hi[a]) - origin[a]) / d[a];
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    const std::optional<float> hit = slab(box, origin, d);
    if (hit) {
      ASSERT_FALSE(std::isnan(*hit));
    }
    const double margin = 1e-5 * std::max(1.0, t1);
    if (t1 - t0 > margin) {
      ++checked;
      false_misses += hit ? 0 : 1;
    } else if (t0 - t1 > margin) {
      ++checked;
      false_hits += hit ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 140000);
  EXPECT_EQ(false_misses, 0);
  EXPECT_EQ(false_hits, 0);
}

}  // namespace
}  // namespace rt
