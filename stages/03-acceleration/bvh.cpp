#include "03-acceleration/bvh.h"

#include "common/error.h"
#include "common/task.h"

#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <future>
#include <new>
#include <system_error>
#include <thread>

namespace rt {

void* allocate_huge(size_t bytes) {
  constexpr size_t kPage = CacheLineAllocator<char>::kHugePage;
  const size_t rounded = (bytes + kPage - 1) / kPage * kPage;  // aligned_alloc wants a multiple
  void* p = std::aligned_alloc(kPage, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  // A hint: where transparent huge pages are "madvise" only (Debian's default), this is what asks
  // for them. Refused or not, the memory is the same.
  madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

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

struct BuildPrimitive {
  Aabb bounds;
  Vec3 centroid;
  std::uint32_t index;
};
using Iterator = std::vector<BuildPrimitive>::iterator;

// Task stage3.bvh.median_split. Put the half of [begin, end) with the smaller centroids along
// `axis` first, in O(n) on average: std::nth_element (introselect) does exactly this. Summed over
// a level of the tree it touches every primitive once, n + n/2 + n/4 + ... < 2n per path, so the
// whole build is O(n log n) without a single full sort.
Iterator split_median(Iterator begin, Iterator end, int axis) {
  const Iterator middle = begin + (end - begin) / 2;
  // BEGIN TASK stage3.bvh.median_split
  std::nth_element(begin, middle, end, [axis](const BuildPrimitive& a, const BuildPrimitive& b) {
    return a.centroid[axis] < b.centroid[axis];
  });
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.median_split");
  // (void)axis;  // any halving terminates: the tree is valid, only slow to traverse
  // END TASK
  return middle;
}

// Task stage3.bvh.middle_split. Partition at the middle of the centroids' extent along `axis`.
// Returns `end` when every centroid falls on one side (the caller then splits at the median).
Iterator split_middle(Iterator begin, Iterator end, int axis, const Aabb& centroid_bounds) {
  // BEGIN TASK stage3.bvh.middle_split
  const float middle = centroid_bounds.centroid()[axis];
  const Iterator split = std::partition(begin, end, [&](const BuildPrimitive& p) { return p.centroid[axis] < middle; });
  return split == begin ? end : split;
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.middle_split");
  // (void)begin, (void)axis, (void)centroid_bounds;
  // return end;
  // END TASK
}

// Task stage3.bvh.sah_split. Binned SAH: along each axis, drop the centroids into kSahBins equal
// bins, sweep the bins once from each side to get, for every boundary, the box and the count on
// either side, and keep the boundary of least cost over all three axes,
//     C = kTraversalCost + kIntersectionCost (A_left N_left + A_right N_right) / A_node.
// Returns `end` when no split is cheaper than a leaf and the node is small enough to be one;
// otherwise partitions [begin, end) at the best boundary and returns the split point.
Iterator split_sah(Iterator begin, Iterator end, const Aabb& node_bounds, const Aabb& centroid_bounds,
                   const BvhBuildOptions& options) {
  constexpr int kBins = BvhBuildOptions::kSahBins;
  // The bin of a centroid along an axis: kBins equal bins over the centroids' extent, the scale
  // kBins / extent computed once per axis (a multiplication per primitive, not a division).
  // Clamped in float before the conversion: int(NaN) or int(inf) is undefined behaviour, and a box
  // whose extent overflowed to inf would give 0 * inf = NaN (the loader keeps scenes within
  // kMaxCoordinate, common/scene.h; this keeps the builder safe for any input anyway).
  const Vec3 extent = centroid_bounds.extent();
  const Vec3 scale = float(kBins) / extent;
  auto bin_of = [&](const BuildPrimitive& p, int axis) {
    const float bin = (p.centroid[axis] - centroid_bounds.lo[axis]) * scale[axis];
    return bin >= 0.0f ? int(std::min(bin, float(kBins - 1))) : 0;
  };
  float best_area_count = kInfinity;
  int best_axis = -1, best_boundary = 0;
  // BEGIN TASK stage3.bvh.sah_split
  // One pass over the primitives fills the bins of all three axes: near the root the primitives
  // do not fit in the cache, and reading them once instead of three times is most of the build.
  std::array<std::array<Aabb, kBins>, 3> bin_bounds;  // [axis][bin]
  std::array<std::array<int, kBins>, 3> bin_count{};
  for (Iterator p = begin; p != end; ++p)
    for (int axis = 0; axis < 3; ++axis) {
      const int b = bin_of(*p, axis);
      bin_bounds[size_t(axis)][size_t(b)].expand(p->bounds);
      ++bin_count[size_t(axis)][size_t(b)];
    }
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0f)) continue;  // all centroids in one plane: no bins
    // area_count[i]: A N of the bins [0, i] plus A N of the bins [i + 1, kBins), for the boundary
    // after bin i: one sweep from below, one from above.
    const auto& bounds = bin_bounds[size_t(axis)];
    const auto& count = bin_count[size_t(axis)];
    std::array<float, kBins - 1> area_count{};
    Aabb below, above;
    int count_below = 0, count_above = 0;
    for (int i = 0; i + 1 < kBins; ++i) {
      below.expand(bounds[size_t(i)]);
      count_below += count[size_t(i)];
      area_count[size_t(i)] = below.half_area() * float(count_below);
    }
    for (int i = kBins - 1; i >= 1; --i) {
      above.expand(bounds[size_t(i)]);
      count_above += count[size_t(i)];
      area_count[size_t(i - 1)] += above.half_area() * float(count_above);
    }
    for (int i = 0; i + 1 < kBins; ++i)
      if (area_count[size_t(i)] < best_area_count) {
        best_area_count = area_count[size_t(i)];
        best_axis = axis;
        best_boundary = i;
      }
  }
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.sah_split");
  // (void)bin_of;
  // return split_median(begin, end, centroid_bounds.longest_axis());  // the lecture's split until this one is done
  // END TASK
  if (best_axis < 0) return end;
  const float area = node_bounds.half_area();
  const float split_cost = BvhBuildOptions::kTraversalCost +
                           BvhBuildOptions::kIntersectionCost * (area > 0.0f ? best_area_count / area : 0.0f);
  const auto count = int(end - begin);
  if (count <= options.max_leaf_size && leaf_cost(count, options) <= split_cost) return end;
  const Iterator split =
      std::partition(begin, end, [&](const BuildPrimitive& p) { return bin_of(p, best_axis) <= best_boundary; });
  return split == begin ? end : split;
}

// Builds the tree depth first. The two subtrees of a large node may be built at the same time, each
// into a node list of its own, which is then appended to its parent's in the order a serial build
// would have made: the tree is the same, node for node, however many threads build it.
class Builder {
 public:
  // `spawn_levels`: how many more levels may hand a subtree to a thread of its own.
  Builder(std::vector<BuildPrimitive>& primitives, const BvhBuildOptions& options, int spawn_levels)
      : primitives_(primitives), options_(options), spawn_levels_(spawn_levels) {}

  // The whole tree: the root, then one unused node, so that every sibling pair starts at an even
  // index: with the array on a 64-byte boundary, each pair is one cache line.
  Bvh build() && {
    nodes_.reserve(2 * primitives_.size() + 2);
    nodes_.resize(2);
    build_node(0, primitives_.begin(), primitives_.end(), 0);
    Bvh bvh;
    bvh.nodes = std::move(nodes_);
    bvh.order.reserve(primitives_.size());
    for (const BuildPrimitive& p : primitives_) bvh.order.push_back(p.index);
    return bvh;
  }

 private:
  using Nodes = std::vector<BvhNode, CacheLineAllocator<BvhNode>>;

  // A subtree as a node list of its own: its root at 0, its sibling pairs from 1 on.
  Nodes build_subtree(Iterator begin, Iterator end, int depth) && {
    nodes_.reserve(2 * size_t(end - begin));
    nodes_.resize(1);
    build_node(0, begin, end, depth);
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

  // Builds the subtree of [begin, end) into the node at `index`, already allocated.
  void build_node(std::uint32_t index, Iterator begin, Iterator end, int depth) {
    Aabb bounds, centroid_bounds;
    for (Iterator p = begin; p != end; ++p) {
      bounds.expand(p->bounds);
      centroid_bounds.expand(p->centroid);
    }
    const auto count = int(end - begin);
    const int axis = count > 0 ? centroid_bounds.longest_axis() : 0;
    const bool flat = count == 0 || !(centroid_bounds.extent()[axis] > 0.0f);  // all centroids equal

    Iterator split = end;
    if (count > options_.max_leaf_size || (options_.split == SplitMethod::sah && count > 1 && !flat)) {
      if (flat) {
        split = begin + count / 2;  // nothing to tell them apart: any halving terminates
      } else if (depth >= BvhBuildOptions::kMaxFreeDepth || options_.split == SplitMethod::median) {
        split = split_median(begin, end, axis);
      } else if (options_.split == SplitMethod::middle) {
        split = split_middle(begin, end, axis, centroid_bounds);
        if (split == end) split = split_median(begin, end, axis);
      } else {
        split = split_sah(begin, end, bounds, centroid_bounds, options_);
        if (split == end && count > options_.max_leaf_size) split = split_median(begin, end, axis);
      }
    }

    if (split == end || split == begin) {
      nodes_[index] = BvhNode{bounds, std::uint32_t(begin - primitives_.begin()), std::uint16_t(count), 0, 1};
      return;
    }
    const auto first = std::uint32_t(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
    nodes_[index] = BvhNode{bounds, first, 0, std::uint8_t(axis), 0};
    if (spawn_levels_ > 0 && count >= kMinSpawnCount) {
      // The two halves touch disjoint ranges of the primitives and write lists of their own.
      Builder left(primitives_, options_, spawn_levels_ - 1), right(primitives_, options_, spawn_levels_ - 1);
      auto build_left = [&] { return std::move(left).build_subtree(begin, split, depth + 1); };
      std::future<Nodes> left_nodes;
      try {
        left_nodes = std::async(std::launch::async, build_left);
      } catch (const std::system_error&) {  // no thread to be had: build both here
        left_nodes = std::async(std::launch::deferred, build_left);
      }
      const Nodes right_nodes = std::move(right).build_subtree(split, end, depth + 1);
      append(first, left_nodes.get());
      append(first + 1, right_nodes);
      return;
    }
    build_node(first, begin, split, depth + 1);
    build_node(first + 1, split, end, depth + 1);
  }

  // Below this many primitives a subtree builds in well under a millisecond: not worth a thread.
  static constexpr int kMinSpawnCount = 1 << 14;

  std::vector<BuildPrimitive>& primitives_;
  BvhBuildOptions options_;
  int spawn_levels_;
  Nodes nodes_;
};

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& primitive_bounds, const BvhBuildOptions& options) {
  if (options.max_leaf_size < 1 || options.max_leaf_size > 255)
    throw UsageError("BVH leaf size must be in [1, 255], got " + std::to_string(options.max_leaf_size));
  std::vector<BuildPrimitive> primitives;
  primitives.reserve(primitive_bounds.size());
  for (size_t i = 0; i < primitive_bounds.size(); ++i)
    primitives.push_back({primitive_bounds[i], primitive_bounds[i].centroid(), std::uint32_t(i)});
  // With k levels of spawning up to 2^k subtrees are built at once: one level more than the
  // threads need, so that a core whose subtree was the smaller one of an uneven split finds work.
  const int threads = options.build_threads > 0 ? options.build_threads
                                                : int(std::max(1u, std::thread::hardware_concurrency()));
  const int spawn_levels = threads > 1 ? std::bit_width(unsigned(threads - 1)) + 1 : 0;
  return Builder(primitives, options, spawn_levels).build();
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
      stack.push_back({node.offset, depth + 1});
      stack.push_back({node.offset + 1, depth + 1});
    }
  }
  s.mean_leaf_primitives = s.leaves ? double(leaf_primitives) / double(s.leaves) : 0.0;
  return s;
}

}  // namespace rt
