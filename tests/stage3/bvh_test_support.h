// Shared by the stage-3 BVH tests: the builders under test, the meshes, random rays, and the
// comparison of two aggregates.
#pragma once

#include "02-whitted/whitted_scene.h"
#include "03-acceleration/bvh_aggregate.h"
#include "common/obj_loader.h"
#include "common/random.h"

#include "stage3/records.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rt {

using testing::source_path;
using testing::subject;

struct Builder {
  const char* name;
  SplitMethod split;
  int leaf_size;
  bool wide = false;  // traversed as the 4-wide tree collapsed from it
  bool packs = true;  // the 4-wide tree's leaves of triangles stored as packs
  bool compact = false;  // the packs naming their triangles, corners read from the mesh

  BvhBuildOptions options() const {
    BvhBuildOptions o;
    o.split = split;
    o.max_leaf_size = leaf_size;
    o.wide = wide;
    o.triangle_packs = packs;
    o.compact_packs = compact;
    return o;
  }
};
inline void PrintTo(const Builder& b, std::ostream* out) { *out << b.name; }
inline const Builder kBuilders[] = {{"median", SplitMethod::median, 4}, {"middle", SplitMethod::middle, 4},
                             {"sah", SplitMethod::sah, 4},       {"median_leaf1", SplitMethod::median, 1},
                             {"sah_leaf16", SplitMethod::sah, 16},    {"sah_wide", SplitMethod::sah, 4, true},
                             {"median_leaf1_wide", SplitMethod::median, 1, true},
                             {"sah_wide_slots", SplitMethod::sah, 4, true, false},
                             {"sah_wide_compact", SplitMethod::sah, 4, true, true, true}};

// The stage-3 tests search stage 2's kinds: spheres and triangles.
using Primitives = WhittedPrimitives;

inline std::shared_ptr<Primitives> primitives_of(std::vector<TriangleMesh> meshes, std::vector<Sphere> spheres = {}) {
  auto set = std::make_shared<Primitives>();
  int shape = 0;
  for (TriangleMesh& mesh : meshes) set->store_of<TriangleKind>().add_mesh(std::move(mesh), 0, shape++);
  for (const Sphere& s : spheres) set->store_of<SphereKind>().push_back({s, 0, shape++});
  return set;
}

inline const std::shared_ptr<Primitives>& bunny() {
  static const auto set = primitives_of({load_obj(source_path("assets/meshes/stanford-bunny.obj"))});
  return set;
}

// A generated closed mesh (a jittered UV sphere, 1,012 triangles) plus spheres that overlap it.
inline std::shared_ptr<Primitives> mix() {
  return primitives_of({make_uv_sphere(12, 44, 0.3f, 8)},
                       {Sphere{Vec3(1.1f, 0, 0), 0.4f}, Sphere{Vec3(0, 0, 0), 0.5f}, Sphere{Vec3(-1, 1, 0.5f), 0.2f},
                        Sphere{Vec3(0, -1.3f, 0), 0.3f}});
}

inline Aabb bounds_of(const Primitives& set) {
  Aabb box;
  for (const Placed<TriangleMesh>& m : set.store_of<TriangleKind>().meshes)
    for (const Vec3& p : m.geometry.positions) box.expand(p);
  for (const Placed<Sphere>& s : set.store_of<SphereKind>()) box.expand(SphereKind::bounds(s.geometry));
  return box;
}

// Rays from a sphere around the scene aimed into its box (most hit), from inside the box in any
// direction, and some exactly axis-aligned (zero direction components).
inline std::vector<Ray> random_rays(const Primitives& set, int count, std::uint64_t seed) {
  const Aabb box = bounds_of(set);
  const Vec3 centre = box.centroid();
  const float radius = glm::length(box.extent());
  Rng rng(seed, 0, 0);
  auto in_box = [&] { return box.lo + Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * box.extent(); };
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Vec3 origin, direction;
    if (i % 4 == 3) {
      origin = in_box();
      direction = glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
    } else {
      const Vec3 u = glm::normalize(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f);
      origin = centre + radius * u;
      direction = glm::normalize(in_box() - origin);
    }
    if (i % 10 == 5) direction = Vec3(0, 0, direction.z < 0 ? -1.0f : 1.0f);
    rays.push_back(Ray{origin, direction});
  }
  return rays;
}

using Answers = std::vector<std::optional<PrimitiveHit>>;

// An aggregate's closest hits for `rays`, in order.
inline Answers answers_of(const Aggregate& aggregate, const std::vector<Ray>& rays) {
  Answers answers;
  answers.reserve(rays.size());
  for (const Ray& ray : rays) answers.push_back(aggregate.closest_hit(ray, Interval::positive()));
  return answers;
}

// Same hit or miss, same t, and the same primitive unless two primitives are hit at exactly the
// same t (a ray through a shared edge), where either is right.
inline void expect_same_answers(const Answers& truth, const Answers& tested) {
  ASSERT_EQ(truth.size(), tested.size());
  int mismatches = 0, hits = 0;
  for (size_t i = 0; i < truth.size() && mismatches < 5; ++i) {
    const auto& a = truth[i];
    const auto& b = tested[i];
    hits += a ? 1 : 0;
    const bool same_primitive = a && b && a->kind == b->kind && a->index == b->index;
    const bool same = a.has_value() == b.has_value() &&
                      (!a || (a->t == b->t && (!same_primitive || (a->b1 == b->b1 && a->b2 == b->b2))));
    if (!same) {
      ++mismatches;
      ADD_FAILURE() << "ray " << i << ": reference " << (a ? std::to_string(a->t) : "miss") << ", tested "
                    << (b ? std::to_string(b->t) : "miss");
    }
  }
  EXPECT_GT(hits, int(truth.size()) / 3) << "the rays must mostly hit something";
}

// Whether a tree culls: a traversal told that nothing is ever hit (so its range never shrinks) must
// still open only leaves holding a small share of the primitives, averaged over rays aimed at the
// scene. An unfinished split (a tree not sorted by position) or an unfinished traversal (every
// primitive tested) fails here at once, naming the tasks, instead of after minutes of brute force.
// share_opened runs the traversal (inside subject()); tree_culls judges its share.
inline double share_opened(const BvhAggregate<Primitives>& bvh, const Primitives& set) {
  const size_t primitives = bvh.size();
  size_t tested = 0;
  auto count = [&](std::uint32_t, Interval) {
    ++tested;
    return std::optional<float>();
  };
  auto count_leaf = [&](std::uint32_t, std::uint32_t primitives, Interval) {
    tested += primitives & ~BvhAggregate<Primitives>::kPackedLeaf;
    return std::optional<float>();
  };
  const std::vector<Ray> rays = random_rays(set, 64, 11);
  for (const Ray& ray : rays) {
    if (bvh.wide_bvh()) wide_bvh_closest_hit(*bvh.wide_bvh(), ray, Interval::positive(), count_leaf);
    else bvh_closest_hit(bvh.bvh(), ray, Interval::positive(), count);
  }
  return double(tested) / double(rays.size() * primitives);
}

inline ::testing::AssertionResult tree_culls(double share, size_t primitives, double max_share = 0.3) {
  if (share <= max_share) return ::testing::AssertionSuccess() << share;
  return ::testing::AssertionFailure() << "a ray opens leaves holding " << 100.0 * share << "% of the " << primitives
                                       << " primitives: the tree does not cull (tasks stage3.bvh.*_split, "
                                       << "stage3.bvh.closest_hit)";
}

// Every builder's tree culls; then brute force once, and every builder against it: same hit or
// miss, same t, same primitive. The brute force is skipped when a tree does not cull.
inline void expect_builders_agree_with_naive(const std::shared_ptr<Primitives>& set, const std::vector<Ray>& rays) {
  const auto [shares, truth, tested] = subject([&] {
    std::vector<double> culled;
    std::vector<std::unique_ptr<BvhAggregate<Primitives>>> trees;
    for (const Builder& b : kBuilders) {
      trees.push_back(std::make_unique<BvhAggregate<Primitives>>(set, b.options()));
      culled.push_back(share_opened(*trees.back(), *set));
    }
    std::vector<Answers> each;
    if (std::any_of(culled.begin(), culled.end(), [](double share) { return !tree_culls(share, 1); }))
      return std::tuple(culled, Answers{}, each);
    for (const auto& tree : trees) each.push_back(answers_of(*tree, rays));
    return std::tuple(culled, answers_of(NaiveAggregate(set), rays), each);
  });
  ASSERT_EQ(shares.size(), std::size(kBuilders));
  for (size_t i = 0; i < shares.size(); ++i) ASSERT_TRUE(tree_culls(shares[i], set->size())) << kBuilders[i].name;
  ASSERT_EQ(tested.size(), shares.size());
  for (size_t i = 0; i < tested.size(); ++i) {
    SCOPED_TRACE(kBuilders[i].name);
    expect_same_answers(truth, tested[i]);
  }
}

}  // namespace rt
