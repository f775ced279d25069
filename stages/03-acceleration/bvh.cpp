#include "03-acceleration/bvh.h"
#include "03-acceleration/bvh_build.h"

#include "common/error.h"
#include "common/parallel.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <future>
#include <new>
#include <optional>

namespace rt {

float leaf_cost(int count, const BvhBuildOptions& options) {
  if (options.wide && options.triangle_packs && count <= BvhBuildOptions::kPackSize) return BvhBuildOptions::kPackCost;
  return BvhBuildOptions::kIntersectionCost * float(count);
}

SplitMethod split_method_from_name(const std::string& name) {
  if (name == "median") return SplitMethod::median;
  if (name == "middle") return SplitMethod::middle;
  if (name == "sah") return SplitMethod::sah;
  throw UsageError("unknown BVH split '" + name + "' (known: median, middle, sah)");
}

const char* split_method_name(SplitMethod method) {
  switch (method) {
    case SplitMethod::median: return "median";
    case SplitMethod::middle: return "middle";
    case SplitMethod::sah: return "sah";
  }
  return "?";
}

namespace {

using namespace bvh_build;

// Builds the tree depth first. The two subtrees of a large node may be built at the same time: the
// first one here, straight into this node list, where a serial build puts it; the second one on a
// thread of its own, into a list of its own, which is appended once both are done, in the order a
// serial build would have made: the tree is the same, node for node, however many threads build it.
class Builder {
 public:
  // `spawn_depth`: nodes above this depth may hand their second subtree to a thread of its own.
  Builder(BuildPrimitives& primitives, const BvhBuildOptions& options, int spawn_depth)
      : primitives_(primitives), options_(options), spawn_depth_(spawn_depth) {}

  // The whole tree: the root, then one unused node, so that every sibling pair starts at an even
  // index: with the array on a 64-byte boundary, each pair is one cache line.
  Bvh build(const Extent& extent) && {
    nodes_.reserve(2 * primitives_.size() + 2);
    nodes_.resize(2);
    build_node(0, primitives_.begin(), primitives_.end(), extent, 0);
    Bvh bvh;
    bvh.nodes = std::move(nodes_);
    bvh.order.reserve(primitives_.size());
    for (const BuildPrimitive& p : primitives_) bvh.order.push_back(p.index);
    return bvh;
  }

 private:
  using Nodes = std::vector<BvhNode, CacheLineAllocator<BvhNode>>;

  // A subtree as a node list of its own: its root at 0, its sibling pairs from 1 on.
  Nodes build_subtree(Iterator begin, Iterator end, const Extent& extent, int depth) && {
    nodes_.reserve(2 * size_t(end - begin));
    nodes_.resize(1);
    build_node(0, begin, end, extent, depth);
    return std::move(nodes_);
  }

  // Puts a subtree built apart into the node at `index` and appends the rest: its pairs, from 1 on,
  // move to the end of this list, so an interior node's first child moves by the same amount.
  void append(std::uint32_t index, const Nodes& subtree) {
    const auto shift = std::uint32_t(nodes_.size()) - 1u;
    auto moved = [shift](BvhNode node) {
      if (!node.is_leaf) node.offset += shift;
      return node;
    };
    nodes_[index] = moved(subtree[0]);
    for (size_t i = 1; i < subtree.size(); ++i) nodes_.push_back(moved(subtree[i]));
  }

  // Builds the subtree of [begin, end), whose extent is given, into the node at `index`, already
  // allocated.
  void build_node(std::uint32_t index, Iterator begin, Iterator end, const Extent& extent, int depth) {
    const Aabb bounds = extent.bounds.aabb(), centroid_bounds = extent.centroids.aabb();
    const auto count = int(end - begin);
    const int axis = count > 0 ? centroid_bounds.longest_axis() : 0;
    const bool flat = count == 0 || !(centroid_bounds.extent()[axis] > 0.0f);  // all centroids equal

    std::optional<Split> split;
    // The lecture's splits give a split point only; both sides are then measured.
    auto measured = [&](Iterator at) { return Split{at, measure(begin, at), measure(at, end)}; };
    if (count > options_.max_leaf_size || (options_.split == SplitMethod::sah && count > 1 && !flat)) {
      if (flat) {
        split = measured(begin + count / 2);  // nothing to tell them apart: any halving terminates
      } else if (depth >= BvhBuildOptions::kMaxFreeDepth || options_.split == SplitMethod::median) {
        split = measured(split_median(begin, end, axis));
      } else if (options_.split == SplitMethod::middle) {
        Iterator at = split_middle(begin, end, axis, centroid_bounds);
        if (at == end) at = split_median(begin, end, axis);
        split = measured(at);
      } else {
        split = split_sah(begin, end, bounds, centroid_bounds, options_);
        if (!split && count > options_.max_leaf_size) split = measured(split_median(begin, end, axis));
      }
    }

    if (!split || split->at == begin || split->at == end) {
      nodes_[index] = BvhNode{bounds, std::uint32_t(begin - primitives_.begin()), std::uint16_t(count), 0, 1};
      return;
    }
    const Iterator at = split->at;
    const auto first = std::uint32_t(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
    nodes_[index] = BvhNode{bounds, first, 0, std::uint8_t(axis), 0};
    if (depth < spawn_depth_ && count >= kMinSpawnCount) {
      // The two halves touch disjoint ranges of the primitives. Only the second one's nodes are
      // copied afterwards (building both apart, as this did before, copied every node once per
      // level of spawning: 24 MB each at 10^6 triangles).
      Builder second(primitives_, options_, spawn_depth_);
      std::future<Nodes> second_nodes =
          start_on_thread([&] { return std::move(second).build_subtree(at, end, split->right, depth + 1); });
      build_node(first, begin, at, split->left, depth + 1);
      append(first + 1, second_nodes.get());
      return;
    }
    build_node(first, begin, at, split->left, depth + 1);
    build_node(first + 1, at, end, split->right, depth + 1);
  }

  // Below this many primitives a subtree builds in well under a millisecond: not worth a thread.
  static constexpr int kMinSpawnCount = 1 << 14;

  BuildPrimitives& primitives_;
  BvhBuildOptions options_;
  int spawn_depth_;
  Nodes nodes_;
};

}  // namespace

Bvh build_bvh(std::span<const Aabb> primitive_bounds, const BvhBuildOptions& options) {
  if (options.max_leaf_size < 1 || options.max_leaf_size > 255)
    throw UsageError("BVH leaf size must be in [1, 255], got " + std::to_string(options.max_leaf_size));
  BuildPrimitives primitives;
  primitives.reserve(primitive_bounds.size());
  Extent extent;
  for (size_t i = 0; i < primitive_bounds.size(); ++i) {
    primitives.push_back({primitive_bounds[i], primitive_bounds[i].centroid(), std::uint32_t(i)});
    extent.add(primitives.back());
  }
  // With k levels of spawning up to 2^k subtrees are built at once: one level more than the
  // threads need, so that a core whose subtree was the smaller one of an uneven split finds work.
  const int threads = resolve_thread_count(options.build_threads);
  const int spawn_depth = threads > 1 ? std::bit_width(unsigned(threads - 1)) + 1 : 0;
  return Builder(primitives, options, spawn_depth).build(extent);
}

BvhStats Bvh::stats() const {
  BvhStats s;
  if (nodes.empty()) return s;
  const float root_area = nodes[0].bounds.half_area();
  size_t leaf_primitives = 0;
  // Depth-first walk with explicit depths.
  std::vector<std::pair<std::uint32_t, size_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    const BvhNode& node = nodes[index];
    s.depth = std::max(s.depth, depth);
    ++s.nodes;
    const double relative_area = root_area > 0.0f ? double(node.bounds.half_area() / root_area) : 1.0;
    if (node.is_leaf) {
      ++s.leaves;
      leaf_primitives += node.count;
      s.max_leaf_primitives = std::max(s.max_leaf_primitives, size_t(node.count));
      s.sah_cost += relative_area * BvhBuildOptions::kIntersectionCost * node.count;
    } else {
      s.sah_cost += relative_area * BvhBuildOptions::kTraversalCost;
      // The first child on top: the walk then goes through the nodes in the order the builder
      // wrote them, and reads the array front to back instead of jumping (4x faster on 10^6).
      stack.push_back({node.offset + 1, depth + 1});
      stack.push_back({node.offset, depth + 1});
    }
  }
  s.mean_leaf_primitives = s.leaves ? double(leaf_primitives) / double(s.leaves) : 0.0;
  return s;
}

}  // namespace rt
