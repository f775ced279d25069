// Stage 3: the bounding volume hierarchy. Every builder produces the same flattened tree, so one
// traversal serves all of them, and they differ only in where they split.
#pragma once

#include "03-acceleration/aabb.h"
#include "common/cache_line_allocator.h"
#include "common/function_ref.h"
#include "common/parallel.h"

#include <cstdint>
#include <cstdlib>
#include <functional>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rt {

enum class SplitMethod {
  median,  // the lecture's: longest axis of the centroids' box, at the median centroid (nth_element)
  middle,  // the spatial middle of the centroids' box along its longest axis
  sah,     // binned surface area heuristic (Wald, "On fast Construction of SAH-based Bounding
           // Volume Hierarchies", IEEE Symposium on Interactive Ray Tracing 2007)
};

// "median" -> SplitMethod::median, ...; throws UsageError for an unknown name.
SplitMethod split_method_from_name(const std::string& name);
const char* split_method_name(SplitMethod method);

struct BvhBuildOptions {
  SplitMethod split = SplitMethod::sah;
  int max_leaf_size = 4;  // a node with more primitives is always split
  // Collapse the binary tree into a 4-wide one for traversal (wide_bvh.h). Same leaves, same
  // answers; fewer, cheaper box tests per ray.
  bool wide = false;
  // In the 4-wide tree, store each leaf of one to four triangles as a pack (02-whitted/
  // triangle_pack.h), tested in one SIMD test; false keeps every leaf slot by slot. The SAH
  // builder then prices a leaf of up to kPackSize primitives as one pack test (leaf_cost).
  bool triangle_packs = true;
  // Store each pack as its triangles' numbers and their corners' vertex numbers in the mesh (48
  // bytes) instead of the corners themselves (144 + 16), and gather the corners from the mesh at
  // every test: Embree's "compact" layout, 40 % less memory in all, as fast on the bunny and about
  // 1.2x slower at 10^6 triangles (docs/stage3.md, ladder step 12). A pack then holds triangles of
  // one mesh whose corners' numbers lie within 65,535 of each other; any other leaf keeps its
  // slots (as do the Cornell box's, which mix quads).
  bool compact_packs = false;
  // Threads that may build subtrees at once; 0: one per core. The tree is the same for any count.
  int build_threads = 0;
  // SAH cost model (MacDonald & Booth 1990): C(split) = kTraversalCost + kIntersectionCost *
  // sum over children of (A_child / A_node) * count_child, against C(leaf) = count *
  // kIntersectionCost. The ratio is what matters. In registers a box test is about a tenth of a
  // watertight triangle test, but a node visit on a large mesh waits on memory, and measured on
  // the bunny and a 10^6-triangle mesh (docs/stage3.md) 1 : 1 traverses faster than pbrt-v3's
  // 1/8 : 1 (1.24 vs 1.43 us per incoherent ray on the bunny), with fewer, fuller leaves.
  static constexpr float kTraversalCost = 1.0f;
  static constexpr float kIntersectionCost = 1.0f;
  // A pack test of up to four triangles, against one triangle test. Measured (docs/stage3.md, the
  // speed ladder, step 9): 1 to 2 build the same bunny tree and trace the meshes 2 % faster than
  // 2.5, but make the Cornell box's leaves of big wall triangles so large that its paths take 5 %
  // more instructions; 2.5 takes 3 % fewer than without packs; from 3 on, pairs of triangles are
  // split into packs of one, and every scene is slower.
  static constexpr float kPackCost = 2.5f;
  static constexpr int kPackSize = 4;
  static constexpr int kSahBins = 16;
  // Below this depth every builder's own split is used; from it on, splits fall back to the
  // median, which halves the primitives, so depth <= kMaxFreeDepth + ceil(log2(n)) < kStackSize.
  static constexpr int kMaxFreeDepth = 36;
};

// The SAH cost of a leaf of `count` primitives: a test per primitive, or, where the leaves become
// triangle packs (a 4-wide tree with triangle_packs), one pack test for up to kPackSize of them.
float leaf_cost(int count, const BvhBuildOptions& options);

// 32 bytes, two to a cache line. The two children of an interior node are stored side by side,
// so only the first one's index is kept, and the traversal, which tests both children's boxes at
// their parent, reads one cache line per interior node.
struct BvhNode {
  Aabb bounds;               // 24 bytes
  std::uint32_t offset;      // leaf: first entry in Bvh::order; interior: index of the first child
  std::uint16_t count;       // leaf: number of primitives (0 only for an empty tree); interior: 0
  std::uint8_t axis;         // interior: the split axis (kept for analysis; traversal orders by entry t)
  std::uint8_t is_leaf;
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes");

struct BvhStats {
  size_t nodes = 0, leaves = 0, depth = 0, max_leaf_primitives = 0;
  double mean_leaf_primitives = 0.0;
  double sah_cost = 0.0;  // the tree's SAH cost with the constants above, per ray through the root
};

struct Bvh {
  // nodes[0] is the root; nodes[1] is unused (padding); then sibling pairs (2k, 2k + 1).
  std::vector<BvhNode, CacheLineAllocator<BvhNode>> nodes;
  std::vector<std::uint32_t, CacheLineAllocator<std::uint32_t>> order;  // primitive indices in leaf order

  BvhStats stats() const;
  // Traversal needs a stack of one entry per level below the root.
  static constexpr int kStackSize = 64;
};

// Builds a BVH over primitives given by their bounding boxes. Any input terminates with a valid
// tree: no primitives (one empty leaf), one primitive, all centroids equal, empty or flat boxes.
Bvh build_bvh(std::span<const Aabb> primitive_bounds, const BvhBuildOptions& options);

// Task stage3.bvh.closest_hit. Iterative traversal with a fixed stack. At an interior node, test
// both children's boxes against the current range; go on into the nearer one (smaller entry t)
// and push the other with its entry t; in a leaf, test each primitive and shrink range.max to
// every hit. A pushed node whose entry t is beyond the nearest hit found since is dropped
// unread: that is where the shrinking range pays.
// `hit_primitive(slot, range)` returns the hit distance, within `range`, of the primitive in leaf
// slot `slot` (the primitive bvh.order[slot]; slots let a caller keep its primitive data in leaf
// order, next to each other in memory). Returns the nearest (t, slot).
std::optional<std::pair<float, std::uint32_t>> bvh_closest_hit(
    const Bvh& bvh, const Ray& ray, Interval range, FunctionRef<std::optional<float>(std::uint32_t, Interval)> hit_primitive);

// Task stage3.bvh.any_hit. The same walk for shadow rays, stopping at the first primitive hit in
// range: no ordering, no shrinking, no record. `hits_primitive(slot, range)` says whether the primitive
// in leaf slot `slot` (the primitive bvh.order[slot]) is hit within `range`.
bool bvh_any_hit(const Bvh& bvh, const Ray& ray, Interval range, FunctionRef<bool(std::uint32_t, Interval)> hits_primitive);

}  // namespace rt
