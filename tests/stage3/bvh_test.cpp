#include "stage3/bvh_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace rt {
namespace {

class Builders : public ::testing::TestWithParam<Builder> {
 protected:
  BvhBuildOptions options() const { return GetParam().options(); }
};

TEST_P(Builders, AgreeWithTheSahTreeOnTheBunny) {
  const auto [shares, truth, answers] = subject([&] {
    const BvhAggregate reference(bunny(), BvhBuildOptions{}), tested(bunny(), options());
    const std::vector<double> culled{share_opened(reference, *bunny()), share_opened(tested, *bunny())};
    if (!tree_culls(culled[0], 1) || !tree_culls(culled[1], 1)) return std::tuple(culled, Answers{}, Answers{});
    const std::vector<Ray> rays = random_rays(*bunny(), 100000, 3);
    return std::tuple(culled, answers_of(reference, rays), answers_of(tested, rays));
  });
  ASSERT_EQ(shares.size(), 2u);
  ASSERT_TRUE(tree_culls(shares[0], bunny()->size()));
  ASSERT_TRUE(tree_culls(shares[1], bunny()->size()));
  ASSERT_EQ(truth.size(), 100000u);
  expect_same_answers(truth, answers);
}

TEST_P(Builders, AnyHitAgreesWithClosestHit) {
  const auto set = mix();
  const std::vector<Ray> rays = random_rays(*set, 20000, 4);
  std::vector<Interval> ranges;
  Rng rng(6, 0, 0);
  for (size_t i = 0; i < rays.size(); ++i) ranges.push_back(Interval{0.0f, 4.0f * rng.uniform()});
  // Per ray: (occluded, closest hit found).
  const auto [share, answers] = subject([&] {
    const BvhAggregate bvh(set, options());
    std::vector<std::pair<bool, bool>> each;
    for (size_t i = 0; i < rays.size(); ++i)
      each.push_back({bvh.occluded(rays[i], ranges[i]), bvh.closest_hit(rays[i], ranges[i]).has_value()});
    return std::pair(share_opened(bvh, *set), each);
  });
  ASSERT_TRUE(tree_culls(share, set->size()));
  ASSERT_EQ(answers.size(), rays.size());
  int occluded = 0;
  for (const auto& [blocked, hit] : answers) {
    EXPECT_EQ(blocked, hit);
    occluded += blocked ? 1 : 0;
  }
  EXPECT_GT(occluded, 1000);
  EXPECT_LT(occluded, 19000);
}

// A ray with a NaN or an infinity in it (a lens of 10^8 units, a hit record gone wrong) meets
// nothing, in every tree. The slab test ignores NaN operands, so such a ray would enter every box:
// in the 4-wide tree the empty slots of a node too (one sphere leaves three of the root's four
// empty), whose child is no node at all.
TEST_P(Builders, RaysWithANanOrAnInfinityMeetNothing) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const Ray rays[] = {{Vec3(nan), Vec3(nan)}, {Vec3(0.0f, 0.0f, -5.0f), Vec3(0.0f, nan, 1.0f)},
                      {Vec3(nan, 0.0f, -5.0f), Vec3(0.0f, 0.0f, 1.0f)}, {Vec3(0.0f, 0.0f, -inf), Vec3(0.0f, 0.0f, 1.0f)},
                      {Vec3(0.0f, 0.0f, -5.0f), Vec3(0.0f, 0.0f, inf)}};
  const auto one_sphere = primitives_of({}, {Sphere{Vec3(0.0f), 1.0f}});
  ASSERT_TRUE(subject([&] {
    return BvhAggregate(one_sphere, options())
        .closest_hit(Ray{Vec3(0.0f, 0.0f, -5.0f), Vec3(0.0f, 0.0f, 1.0f)}, Interval::positive())
        .has_value();
  }));  // the finite ray does
  for (const auto& set : {one_sphere, mix()}) {
    // Per ray: (closest hit found, occluded).
    const auto answers = subject([&] {
      const BvhAggregate bvh(set, options());
      std::vector<std::pair<bool, bool>> each;
      for (const Ray& ray : rays)
        each.push_back({bvh.closest_hit(ray, Interval::positive()).has_value(), bvh.occluded(ray, Interval::positive())});
      return each;
    });
    for (const auto& [hit, blocked] : answers) {
      EXPECT_FALSE(hit);
      EXPECT_FALSE(blocked);
    }
  }
}

TEST(BvhAgainstNaive, MixOfSpheresAndTriangles) {
  const auto set = mix();
  expect_builders_agree_with_naive(set, random_rays(*set, 100000, 1));
}

TEST(BvhAgainstNaive, GeneratedMesh) {
  const auto set = primitives_of({make_uv_sphere(12, 24, 0.5f, 12)});  // 528 triangles, jittered
  expect_builders_agree_with_naive(set, random_rays(*set, 100000, 7));
}

TEST(BvhAgainstNaive, Bunny) {
  // 1,000 rays against all 69,451 triangles by brute force; the 100,000-ray version is
  // BunnyFull.* (label "slow": ctest --preset slow).
  expect_builders_agree_with_naive(bunny(), random_rays(*bunny(), 1000, 2));
}

// Every node's box is exactly the box around its children's (a leaf's: its primitives'; a larger
// box only costs visits, so nothing else would notice), every primitive is in exactly one leaf,
// no interior node is empty, and the depth stays within the bound that the fixed traversal stack
// relies on.
void expect_valid_tree(const Bvh& bvh, const std::vector<Aabb>& bounds) {
  const size_t n = bounds.size();
  ASSERT_FALSE(bvh.nodes.empty());
  std::vector<int> seen(n, 0);
  std::vector<std::pair<std::uint32_t, int>> stack{{0, 0}};
  int depth = 0;
  while (!stack.empty()) {
    const auto [index, d] = stack.back();
    stack.pop_back();
    ASSERT_LT(index, bvh.nodes.size());
    const BvhNode& node = bvh.nodes[index];
    depth = std::max(depth, d);
    if (node.is_leaf) {
      if (n > 0) {
        EXPECT_GT(node.count, 0) << "empty leaf";
      }
      Aabb tight;
      for (std::uint32_t slot = node.offset; slot < node.offset + node.count; ++slot) {
        ASSERT_LT(slot, n);
        ++seen[bvh.order[slot]];
        tight.expand(bounds[bvh.order[slot]]);
      }
      EXPECT_TRUE(node.bounds.lo == tight.lo && node.bounds.hi == tight.hi) << "leaf " << index << "'s box is not tight";
    } else {
      Aabb tight;
      for (const std::uint32_t child : {node.offset, node.offset + 1}) {
        ASSERT_LT(child, bvh.nodes.size());
        tight.expand(bvh.nodes[child].bounds);
        stack.push_back({child, d + 1});
      }
      EXPECT_TRUE(node.bounds.lo == tight.lo && node.bounds.hi == tight.hi) << "node " << index << "'s box is not tight";
    }
  }
  for (size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "primitive " << i;
  const int bound = BvhBuildOptions::kMaxFreeDepth + int(std::ceil(std::log2(double(std::max<size_t>(n, 1))))) + 1;
  EXPECT_LE(depth, bound);
  EXPECT_LT(depth, Bvh::kStackSize);
}

// The 4-wide tree holds the binary tree's leaves, each exactly once; every child's box contains
// what lies below it; unused children have empty boxes; it is no deeper than the binary tree.
void expect_valid_wide_tree(const WideBvh& wide, const Bvh& bvh, const std::vector<Aabb>& bounds) {
  if (bounds.empty()) {
    EXPECT_TRUE(wide.nodes.empty());
    return;
  }
  std::vector<int> seen(bounds.size(), 0);
  // (node, the box its parent holds for it, depth)
  std::vector<std::tuple<std::uint32_t, Aabb, int>> stack{{0, wide.bounds, 0}};
  int depth = 0;
  while (!stack.empty()) {
    const auto [index, parent_box, d] = stack.back();
    stack.pop_back();
    ASSERT_LT(index, wide.nodes.size());
    const WideBvhNode& node = wide.nodes[index];
    depth = std::max(depth, d);
    for (int i = 0; i < WideBvhNode::kWidth; ++i) {
      const Aabb box{Vec3(node.bounds[0][0][i], node.bounds[0][1][i], node.bounds[0][2][i]),
                     Vec3(node.bounds[1][0][i], node.bounds[1][1][i], node.bounds[1][2][i])};
      if (box.is_empty() && node.count[i] == 0 && !(node.child[i] > index)) continue;  // unused
      EXPECT_TRUE(parent_box.contains(box));
      if (node.count[i] == 0) {
        ASSERT_GT(node.child[i], index) << "children are made after their parent";
        stack.push_back({node.child[i], box, d + 1});
        continue;
      }
      for (std::uint32_t slot = node.child[i]; slot < node.child[i] + node.count[i]; ++slot) {
        ASSERT_LT(slot, bounds.size());
        ++seen[bvh.order[slot]];
        EXPECT_TRUE(box.contains(bounds[bvh.order[slot]]));
      }
    }
  }
  for (size_t i = 0; i < bounds.size(); ++i) EXPECT_EQ(seen[i], 1) << "primitive " << i;
  EXPECT_LE(size_t(depth + 1), bvh.stats().depth + 1);
}

std::vector<Aabb> triangle_bounds(const TriangleMesh& mesh) {
  std::vector<Aabb> bounds;
  for (const auto& c : mesh.triangles) {
    Aabb box;
    for (const auto v : c) box.expand(mesh.positions[v]);
    bounds.push_back(box);
  }
  return bounds;
}

TEST_P(Builders, TreesAreValidOnRealAndDegenerateInput) {
  std::vector<std::vector<Aabb>> inputs;
  inputs.push_back(triangle_bounds(bunny()->store_of<TriangleKind>().meshes[0].geometry));
  inputs.push_back({});                                        // no primitives
  inputs.push_back({Aabb{Vec3(1), Vec3(2)}});                  // one
  inputs.push_back(std::vector<Aabb>(1000, Aabb{Vec3(1), Vec3(2)}));  // all centroids equal
  inputs.push_back(std::vector<Aabb>(300, Aabb{Vec3(1), Vec3(1)}));   // all points, equal
  std::vector<Aabb> flat;  // zero-area triangles along a line, and exponentially spaced boxes
  for (int i = 0; i < 1000; ++i) flat.push_back(Aabb{Vec3(float(i), 0, 0), Vec3(float(i) + 1, 0, 0)});
  for (int i = 0; i < 100; ++i) flat.push_back(Aabb{Vec3(std::ldexp(1.0f, i - 50)), Vec3(std::ldexp(1.0f, i - 50))});
  inputs.push_back(flat);
  for (const auto& input : inputs) {
    SCOPED_TRACE(std::to_string(input.size()) + " primitives");
    const Bvh bvh = subject([&] { return build_bvh(input, options()); });
    expect_valid_tree(bvh, input);
    if (options().wide) expect_valid_wide_tree(collapse_to_wide(bvh), bvh, input);
  }
}

TEST_P(Builders, DegenerateTrianglesNeitherHitNorBreakTheTree) {
  // Ten per cent of the triangles collapsed to lines and points: the closest hits are those of
  // the mesh without them.
  TriangleMesh clean = make_uv_sphere(10, 20, 0.2f, 4), dirty = clean;
  for (size_t k = 0; k < clean.triangles.size(); k += 10) {
    dirty.positions.push_back(Vec3(0.1f * float(k), 0, 0));
    const auto p = std::uint32_t(dirty.positions.size() - 1);
    dirty.triangles.push_back({p, p, p});
    dirty.triangles.push_back({clean.triangles[k][0], clean.triangles[k][1], clean.triangles[k][1]});
  }
  const auto clean_set = primitives_of({clean}), dirty_set = primitives_of({dirty});
  const std::vector<Ray> rays = random_rays(*clean_set, 5000, 9);
  const auto [truth, answers] = subject([&] {
    return std::pair(answers_of(NaiveAggregate(clean_set), rays), answers_of(BvhAggregate(dirty_set, options()), rays));
  });
  ASSERT_EQ(answers.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const auto &a = truth[i], &b = answers[i];
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->t, b->t);
      EXPECT_LT(b->index, clean.triangles.size()) << "a degenerate triangle was hit";
    }
  }
}

TEST_P(Builders, ThreadsBuildTheSameTreeAsOne) {
  // The bunny has enough triangles for its first levels' subtrees to be built on threads of their
  // own; the tree must come out node for node as the serial build makes it.
  const std::vector<Aabb> bounds = triangle_bounds(bunny()->store_of<TriangleKind>().meshes[0].geometry);
  BvhBuildOptions serial = options(), parallel = options();
  serial.build_threads = 1;
  parallel.build_threads = 4;
  const Bvh one = subject([&] { return build_bvh(bounds, serial); });
  const Bvh four = subject([&] { return build_bvh(bounds, parallel); });
  ASSERT_EQ(one.nodes.size(), four.nodes.size());
  EXPECT_EQ(one.order, four.order);
  for (size_t i = 0; i < one.nodes.size(); ++i) {
    const BvhNode &a = one.nodes[i], &b = four.nodes[i];
    ASSERT_TRUE(a.bounds.lo == b.bounds.lo && a.bounds.hi == b.bounds.hi && a.offset == b.offset &&
                a.count == b.count && a.axis == b.axis && a.is_leaf == b.is_leaf)
        << "node " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Bvh, Builders, ::testing::ValuesIn(kBuilders), [](const auto& info) { return std::string(info.param.name); });

TEST(SahSplit, SeparatesTwoClustersOfUnequalSize) {
  // Four unit boxes at x = 0 and twelve at x = 100, their centroids on one line (y and z equal):
  // the SAH's root split must part the clusters, 4 | 12, where the median would put 8 | 8 and
  // give one child a box 101 wide. Every boundary between used bins must be priced, the last
  // included, and an axis along which the centroids spread must be binned.
  std::vector<Aabb> boxes;
  for (int i = 0; i < 16; ++i) {
    const float x = i < 4 ? 0.0f : 100.0f;
    boxes.push_back(Aabb{Vec3(x, 0, 0), Vec3(x + 1, 1, 1)});
  }
  BvhBuildOptions options;
  options.split = SplitMethod::sah;
  const Bvh bvh = subject([&] { return build_bvh(boxes, options); });
  ASSERT_FALSE(bvh.nodes.empty());
  const BvhNode& root = bvh.nodes[0];
  ASSERT_FALSE(root.is_leaf);
  ASSERT_LT(root.offset + 1, bvh.nodes.size());
  const BvhNode &a = bvh.nodes[root.offset], &b = bvh.nodes[root.offset + 1];
  EXPECT_LE(a.bounds.hi.x - a.bounds.lo.x, 1.0f);
  EXPECT_LE(b.bounds.hi.x - b.bounds.lo.x, 1.0f);
}

// The point of the ordered walk (bvh.h): into the nearer child first, so that the first hit shrinks
// the range and every farther node is dropped unread. 256 unit boxes in a row, one per leaf, seen
// end on from either side: the nearest box is the first primitive tested and the last, since every
// other box lies beyond it. Walking into the farther child first tests all 256 (each hit nearer
// than the one before); the lecture's unordered walk tests them all too.
TEST(BvhTraversal, EntersTheNearerChildFirstAndDropsWhatLiesBeyondTheHit) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 256; ++i) boxes.push_back(Aabb{Vec3(2.0f * float(i), 0, 0), Vec3(2.0f * float(i) + 1, 1, 1)});
  for (const SplitMethod split : {SplitMethod::median, SplitMethod::middle, SplitMethod::sah}) {
    BvhBuildOptions options;
    options.split = split;
    options.max_leaf_size = 1;
    for (const float direction : {1.0f, -1.0f}) {
      const Ray ray{Vec3(direction > 0 ? -10.0f : 600.0f, 0.5f, 0.5f), Vec3(direction, 0, 0)};
      // The primitives tested, in order, and the primitive hit.
      const auto [tested, hit] = subject([&] {
        const Bvh bvh = build_bvh(boxes, options);
        std::vector<std::uint32_t> order;
        const auto hit_box = [&](std::uint32_t slot, Interval range) -> std::optional<float> {
          order.push_back(bvh.order.at(slot));
          const Aabb& box = boxes.at(bvh.order.at(slot));
          const float t = direction > 0 ? box.lo.x - ray.origin.x : ray.origin.x - box.hi.x;
          return range.surrounds(t) ? std::optional<float>(t) : std::nullopt;
        };
        const auto found = bvh_closest_hit(bvh, ray, Interval::positive(), hit_box);
        return std::pair(order, found ? std::optional<std::uint32_t>(bvh.order.at(found->second)) : std::nullopt);
      });
      const std::uint32_t nearest = direction > 0 ? 0 : 255;
      ASSERT_TRUE(hit);
      EXPECT_EQ(*hit, nearest);
      EXPECT_EQ(tested, std::vector<std::uint32_t>{nearest}) << "split " << int(split) << ", direction " << direction;
    }
  }
}

TEST(BvhLayout, NodesAreThirtyTwoBytes) {
  EXPECT_EQ(sizeof(BvhNode), 32u);
  EXPECT_EQ(alignof(BvhNode), 4u);
  EXPECT_EQ(sizeof(WideBvhNode), 128u);  // four boxes, two cache lines
}

// The SAH prices a leaf of up to four primitives as one pack test only where leaves become packs.
TEST(BvhLayout, LeafCostIsOnePackTestForUpToFourPrimitives) {
  const BvhBuildOptions packed{.wide = true}, slots{.wide = true, .triangle_packs = false}, binary{};
  EXPECT_EQ(leaf_cost(1, packed), BvhBuildOptions::kPackCost);
  EXPECT_EQ(leaf_cost(4, packed), BvhBuildOptions::kPackCost);
  EXPECT_EQ(leaf_cost(5, packed), 5.0f * BvhBuildOptions::kIntersectionCost);
  EXPECT_EQ(leaf_cost(4, slots), 4.0f * BvhBuildOptions::kIntersectionCost);
  EXPECT_EQ(leaf_cost(3, binary), 3.0f * BvhBuildOptions::kIntersectionCost);
}

TEST(BvhLayout, SahBeatsTheOtherBuildersOnItsOwnCostModel) {
  // The SAH tree minimises the expected cost per ray greedily; on the bunny it must come out
  // cheaper than the median and middle trees by the same measure.
  std::vector<Aabb> bounds = triangle_bounds(bunny()->store_of<TriangleKind>().meshes[0].geometry);
  auto cost = [&](SplitMethod split) {
    BvhBuildOptions o;
    o.split = split;
    return subject([&] { return build_bvh(bounds, o); }).stats().sah_cost;
  };
  EXPECT_LT(cost(SplitMethod::sah), cost(SplitMethod::median));
  EXPECT_LT(cost(SplitMethod::sah), cost(SplitMethod::middle));
}

}  // namespace
}  // namespace rt
