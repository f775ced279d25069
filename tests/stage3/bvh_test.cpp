#include "stage3/bvh_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rt {
namespace {

class Builders : public ::testing::TestWithParam<Builder> {
 protected:
  BvhBuildOptions options() const {
    BvhBuildOptions o;
    o.split = GetParam().split;
    o.max_leaf_size = GetParam().leaf_size;
    return o;
  }
};

TEST_P(Builders, AgreeWithTheSahTreeOnTheBunny) {
  BvhBuildOptions sah;
  expect_same_answers(BvhAggregate(bunny(), sah), BvhAggregate(bunny(), options()), random_rays(*bunny(), 100000, 3));
}

TEST_P(Builders, AnyHitAgreesWithClosestHit) {
  const auto set = mix();
  const BvhAggregate bvh(set, options());
  Rng rng(6, 0, 0);
  int occluded = 0;
  for (const Ray& ray : random_rays(*set, 20000, 4)) {
    const Interval range{0.0f, 4.0f * rng.uniform()};
    const bool blocked = bvh.occluded(ray, range);
    EXPECT_EQ(blocked, bvh.closest_hit(ray, range).has_value());
    occluded += blocked ? 1 : 0;
  }
  EXPECT_GT(occluded, 1000);
  EXPECT_LT(occluded, 19000);
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

// Every node's box holds its children's, every primitive is in exactly one leaf, no interior node
// is empty, and the depth stays within the bound that the fixed traversal stack relies on.
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
      for (std::uint32_t slot = node.offset; slot < node.offset + node.count; ++slot) {
        ASSERT_LT(slot, n);
        ++seen[bvh.order[slot]];
        EXPECT_TRUE(node.bounds.contains(bounds[bvh.order[slot]]));
      }
    } else {
      for (const std::uint32_t child : {node.offset, node.offset + 1}) {
        ASSERT_LT(child, bvh.nodes.size());
        EXPECT_TRUE(node.bounds.contains(bvh.nodes[child].bounds)) << "child " << child << " outside its parent";
        stack.push_back({child, d + 1});
      }
    }
  }
  for (size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "primitive " << i;
  const int bound = BvhBuildOptions::kMaxFreeDepth + int(std::ceil(std::log2(double(std::max<size_t>(n, 1))))) + 1;
  EXPECT_LE(depth, bound);
  EXPECT_LT(depth, Bvh::kStackSize);
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
  inputs.push_back(triangle_bounds(bunny()->meshes[0].mesh));
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
    expect_valid_tree(build_bvh(input, options()), input);
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
  const BvhAggregate with(dirty_set, options());
  const NaiveAggregate without(clean_set);
  for (const Ray& ray : random_rays(*clean_set, 5000, 9)) {
    const auto a = without.closest_hit(ray, Interval::positive()), b = with.closest_hit(ray, Interval::positive());
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->t, b->t);
      EXPECT_LT(b->triangle, int(clean.triangles.size())) << "a degenerate triangle was hit";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bvh, Builders, ::testing::ValuesIn(kBuilders), [](const auto& info) { return std::string(info.param.name); });

TEST(BvhLayout, NodesAreThirtyTwoBytes) {
  EXPECT_EQ(sizeof(BvhNode), 32u);
  EXPECT_EQ(alignof(BvhNode), 4u);
}

TEST(BvhLayout, SahBeatsTheOtherBuildersOnItsOwnCostModel) {
  // The SAH tree minimises the expected cost per ray greedily; on the bunny it must come out
  // cheaper than the median and middle trees by the same measure.
  std::vector<Aabb> bounds = triangle_bounds(bunny()->meshes[0].mesh);
  auto cost = [&](SplitMethod split) {
    BvhBuildOptions o;
    o.split = split;
    return build_bvh(bounds, o).stats().sah_cost;
  };
  EXPECT_LT(cost(SplitMethod::sah), cost(SplitMethod::median));
  EXPECT_LT(cost(SplitMethod::sah), cost(SplitMethod::middle));
}

}  // namespace
}  // namespace rt
