// Stage 3 beyond the lecture: the 4-wide tree's four-box test, and its leaves stored as triangle
// packs, copied or compact (packed_wide_bvh.h), on any number of build threads.
#include "stage3/bvh_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace rt {
namespace {

TEST(WideBvh, FourBoxTestMatchesTheSlabTestBoxByBox) {
  // Random boxes (some flat, some empty) and rays with zero and negative-zero components: each
  // lane of the four-box test must give exactly what intersect_aabb gives for that box.
  Rng rng(31, 0, 0);
  auto coordinate = [&] { return std::floor(8.0f * rng.uniform()) - 4.0f; };  // on a grid: origins on planes
  for (int trial = 0; trial < 20000; ++trial) {
    WideBvhNode node{};
    Aabb boxes[4];
    for (int i = 0; i < 4; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        const float a = coordinate(), b = coordinate();
        boxes[i].lo[axis] = std::min(a, b);
        boxes[i].hi[axis] = std::max(a, b);
      }
      if (trial % 7 == i) boxes[i] = Aabb{};  // empty
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[0][axis][i] = boxes[i].lo[axis];
        node.bounds[1][axis][i] = boxes[i].hi[axis];
      }
    }
    Vec3 d(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    if (trial % 3 == 0) d[trial % 9 / 3] = (trial % 2) ? 0.0f : -0.0f;
    const Ray ray{Vec3(coordinate(), coordinate(), coordinate()), d};
    const RayInverse inverse(ray);
    const Interval range{0.0f, 10.0f * rng.uniform()};
    float t[4];
    const unsigned hits = intersect_wide_node(node, inverse, range, t);
    ASSERT_LT(hits, 16u);
    const auto slabs = subject([&] {
      std::array<std::optional<float>, 4> each;
      for (int i = 0; i < 4; ++i) each[size_t(i)] = intersect_aabb(boxes[i], inverse, range);
      return each;
    });
    for (int i = 0; i < 4; ++i) {
      const std::optional<float> expected = slabs[size_t(i)];
      ASSERT_EQ((hits >> i & 1u) != 0, expected.has_value()) << "trial " << trial << ", box " << i;
      if (expected) {
        EXPECT_EQ(t[i], *expected);
      }
    }
  }
}

// The leaves of the 4-wide tree, as the aggregate stores them.
struct Leaves {
  size_t packed = 0, unpacked = 0;
  size_t packs_named_beyond_the_last = 0;  // must be 0
};
Leaves leaves_of(const BvhAggregate<Primitives>& bvh) {
  Leaves leaves;
  for (const WideBvhNode& node : bvh.wide_bvh()->nodes)
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      if (node.count[i] == 0) continue;
      const bool pack = (node.count[i] & BvhAggregate<Primitives>::kPackedLeaf) != 0;
      leaves.packed += pack;
      leaves.unpacked += !pack;
      leaves.packs_named_beyond_the_last += pack && node.child[i] >= bvh.packs();
    }
  return leaves;
}
auto record_fields(Leaves& l) { return std::tie(l.packed, l.unpacked, l.packs_named_beyond_the_last); }

// Every leaf of one to four triangles becomes a pack, and only those: a leaf with a sphere keeps
// its slots, and so does every leaf when the scene's triangle test is Moeller-Trumbore (whose
// answers the pack's watertight test would not give) or packs are turned off.
TEST(BvhLayout, WideLeavesOfUpToFourTrianglesArePacks) {
  BvhBuildOptions options{.wide = true};
  auto moller_trumbore = mix();
  moller_trumbore->store_of<TriangleKind>().method = TriangleMethod::moller_trumbore;
  BvhBuildOptions without_packs = options;
  without_packs.triangle_packs = false;
  // The bunny's leaves and packs, the mix's leaves, and the packs with Moeller-Trumbore and with packs off.
  const auto [bunny_leaves, bunny_packs, mixed, packs_moller_trumbore, packs_off] = subject([&] {
    const BvhAggregate bunny_tree(bunny(), options);
    return std::tuple(leaves_of(bunny_tree), bunny_tree.packs(), leaves_of(BvhAggregate(mix(), options)),
                      BvhAggregate(moller_trumbore, options).packs(), BvhAggregate(bunny(), without_packs).packs());
  });
  EXPECT_EQ(bunny_leaves.unpacked, 0u);
  EXPECT_EQ(bunny_leaves.packed, bunny_packs);
  EXPECT_EQ(bunny_leaves.packs_named_beyond_the_last, 0u);
  EXPECT_GT(bunny_leaves.packed, bunny()->size() / 4);

  EXPECT_GT(mixed.packed, 0u);
  EXPECT_GE(mixed.unpacked, 1u);  // the four spheres sit in leaves of their own or with triangles
  EXPECT_LE(mixed.unpacked, 4u);
  EXPECT_EQ(mixed.packs_named_beyond_the_last, 0u);

  EXPECT_EQ(packs_moller_trumbore, 0u);
  EXPECT_EQ(packs_off, 0u);
}

// A fan of 100 triangles around one edge, from vertex 0 to vertex `spread` (the vertices between
// them unused but for the fan's outer corners, 1 ... 100): every leaf's corners spread over
// exactly `spread` vertex numbers.
std::shared_ptr<Primitives> fan_with_spread(std::uint32_t spread) {
  TriangleMesh mesh;
  mesh.positions.resize(spread + 1, Vec3(0.0f));
  mesh.positions[spread] = Vec3(0.0f, 1.0f, 0.0f);
  for (std::uint32_t i = 0; i < 100; ++i) {
    const float angle = 0.06f * float(i);
    mesh.positions[1 + i] = Vec3(std::cos(angle), 0.5f, std::sin(angle));
    mesh.triangles.push_back({0, spread, 1 + i});
  }
  return primitives_of({std::move(mesh)});
}

// Compact packs (BvhBuildOptions::compact_packs) name their triangles and read the corners from the
// mesh: the same answers bit for bit, primitive numbers included, across meshes (two overlapping
// spheres, whose leaves may mix meshes: those keep their slots), where a leaf's corners spread over
// up to 65,535 vertex numbers and beyond (then it keeps its slots), and on the bunny mesh and BVH
// together within 64 bytes per triangle, under two thirds of the memory of copied packs.
TEST(BvhLayout, CompactPacksAnswerAsCopiedOnesInLessMemory) {
  const auto two_meshes = primitives_of({make_uv_sphere(12, 44, 0.3f, 8), make_uv_sphere(10, 30, 0.3f, 9)});
  const auto widest = fan_with_spread(0xffff), too_wide = fan_with_spread(0x10000);
  const BvhBuildOptions copied_options{.wide = true}, compact_options{.wide = true, .compact_packs = true};
  const auto [widest_leaves, too_wide_leaves] = subject([&] {
    return std::pair(leaves_of(BvhAggregate(widest, compact_options)),
                     leaves_of(BvhAggregate(too_wide, compact_options)));
  });
  EXPECT_EQ(widest_leaves.unpacked, 0u);
  EXPECT_EQ(too_wide_leaves.packed, 0u);
  for (const auto& set : {two_meshes, widest, too_wide, bunny()}) {
    const std::vector<Ray> rays = random_rays(*set, 4000, 11);
    // The compact tree's packs, and per tree each ray's closest hit and whether it is occluded.
    const auto [compact_packs, copied_answers, compact_answers, copied_occluded, compact_occluded] = subject([&] {
      const BvhAggregate copied(set, copied_options), compact(set, compact_options);
      std::vector<bool> copied_blocked, compact_blocked;
      for (const Ray& ray : rays) {
        copied_blocked.push_back(copied.occluded(ray, Interval::positive()));
        compact_blocked.push_back(compact.occluded(ray, Interval::positive()));
      }
      return std::tuple(compact.packs(), answers_of(copied, rays), answers_of(compact, rays), copied_blocked,
                        compact_blocked);
    });
    if (set != too_wide) {
      ASSERT_GT(compact_packs, set->size() / 5);
    }
    ASSERT_EQ(copied_answers.size(), rays.size());
    ASSERT_EQ(compact_answers.size(), rays.size());
    ASSERT_EQ(copied_occluded, compact_occluded);
    for (size_t i = 0; i < rays.size(); ++i) {
      const auto &x = copied_answers[i], &y = compact_answers[i];
      ASSERT_EQ(x.has_value(), y.has_value());
      if (x) {
        ASSERT_TRUE(x->t == y->t && x->kind == y->kind && x->index == y->index && x->b1 == y->b1 && x->b2 == y->b2)
            << "t " << x->t << " vs " << y->t << ", triangle " << x->index << " vs " << y->index;
      }
    }
  }
  const auto [copied_meshes, compact_meshes, copied, compact] = subject([&] {
    return std::tuple(leaves_of(BvhAggregate(two_meshes, copied_options)),
                      leaves_of(BvhAggregate(two_meshes, compact_options)),
                      BvhAggregate(bunny(), copied_options).bytes(), BvhAggregate(bunny(), compact_options).bytes());
  });
  EXPECT_EQ(copied_meshes.unpacked, 0u);
  EXPECT_GT(compact_meshes.unpacked, 0u);

  const double triangles = double(bunny()->size());
  const double mesh_bytes = double(bunny()->store_of<TriangleKind>().bytes());
  EXPECT_LT(3 * compact, 2 * copied);
  EXPECT_LE((mesh_bytes + double(compact)) / triangles, 64.0);
}

// The packs are filled in chunks, a chunk per build thread: on any number of threads the 4-wide
// tree, its packs and so every answer come out the same.
TEST(BvhLayout, PacksComeOutTheSameOnAnyNumberOfThreads) {
  const std::vector<Ray> rays = random_rays(*bunny(), 3000, 5);
  // Per tree: its packs, its nodes' (child, count) in order, and its answers.
  const auto trees = subject([&] {
    std::vector<std::tuple<size_t, std::vector<std::pair<std::uint32_t, std::uint32_t>>, Answers>> each;
    for (const int threads : {1, 3}) {
      const BvhAggregate tree(bunny(), BvhBuildOptions{.wide = true, .build_threads = threads});
      std::vector<std::pair<std::uint32_t, std::uint32_t>> children;
      for (const WideBvhNode& node : tree.wide_bvh()->nodes)
        for (int c = 0; c < WideBvhNode::kWidth; ++c) children.push_back({node.child[c], node.count[c]});
      each.push_back({tree.packs(), children, answers_of(tree, rays)});
    }
    return each;
  });
  ASSERT_EQ(trees.size(), 2u);
  const auto& [one_packs, a, one] = trees[0];
  const auto& [three_packs, b, three] = trees[1];
  ASSERT_EQ(one_packs, three_packs);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(a[i] == b[i]) << "node " << i / 4 << " child " << i % 4;
  ASSERT_EQ(one.size(), rays.size());
  ASSERT_EQ(three.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto &x = one[i], &y = three[i];
    ASSERT_EQ(x.has_value(), y.has_value());
    if (x) {
      EXPECT_TRUE(x->t == y->t && x->index == y->index && x->b1 == y->b1 && x->b2 == y->b2);
    }
  }
}

}  // namespace
}  // namespace rt
