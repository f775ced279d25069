#include "03-acceleration/bvh.h"

#include "common/error.h"
#include "common/task.h"

#include <algorithm>
#include <array>

namespace rt {

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
                   int max_leaf_size) {
  constexpr int kBins = BvhBuildOptions::kSahBins;
  // Clamped in float before the conversion: int(NaN) or int(inf) is undefined behaviour, and a box
  // whose extent overflowed to inf would give 0 * inf = NaN (the loader keeps scenes within
  // kMaxCoordinate, common/scene.h; this keeps the builder safe for any input anyway).
  auto bin_of = [&](const BuildPrimitive& p, int axis) {
    const float lo = centroid_bounds.lo[axis], extent = centroid_bounds.extent()[axis];
    const float bin = float(kBins) * ((p.centroid[axis] - lo) / extent);
    return bin >= 0.0f ? int(std::min(bin, float(kBins - 1))) : 0;
  };
  float best_area_count = kInfinity;
  int best_axis = -1, best_boundary = 0;
  // BEGIN TASK stage3.bvh.sah_split
  for (int axis = 0; axis < 3; ++axis) {
    if (!(centroid_bounds.extent()[axis] > 0.0f)) continue;  // all centroids in one plane: no bins
    std::array<Aabb, kBins> bin_bounds;
    std::array<int, kBins> bin_count{};
    for (Iterator p = begin; p != end; ++p) {
      const int b = bin_of(*p, axis);
      bin_bounds[size_t(b)].expand(p->bounds);
      ++bin_count[size_t(b)];
    }
    // area_count[i]: A N of the bins [0, i] plus A N of the bins [i + 1, kBins), for the boundary
    // after bin i: one sweep from below, one from above.
    std::array<float, kBins - 1> area_count{};
    Aabb below, above;
    int count_below = 0, count_above = 0;
    for (int i = 0; i + 1 < kBins; ++i) {
      below.expand(bin_bounds[size_t(i)]);
      count_below += bin_count[size_t(i)];
      area_count[size_t(i)] = below.half_area() * float(count_below);
    }
    for (int i = kBins - 1; i >= 1; --i) {
      above.expand(bin_bounds[size_t(i)]);
      count_above += bin_count[size_t(i)];
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
  if (count <= max_leaf_size && BvhBuildOptions::kIntersectionCost * float(count) <= split_cost) return end;
  const Iterator split =
      std::partition(begin, end, [&](const BuildPrimitive& p) { return bin_of(p, best_axis) <= best_boundary; });
  return split == begin ? end : split;
}

class Builder {
 public:
  Builder(std::vector<BuildPrimitive> primitives, const BvhBuildOptions& options)
      : primitives_(std::move(primitives)), options_(options) {}

  Bvh build() && {
    bvh_.nodes.reserve(2 * primitives_.size() + 2);
    // The root, then one unused node, so that every sibling pair starts at an even index: with
    // the array on a 64-byte boundary, each pair is one cache line.
    bvh_.nodes.resize(2);
    build_node(0, primitives_.begin(), primitives_.end(), 0);
    for (const BuildPrimitive& p : primitives_) bvh_.order.push_back(p.index);
    return std::move(bvh_);
  }

 private:
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
        split = split_sah(begin, end, bounds, centroid_bounds, options_.max_leaf_size);
        if (split == end && count > options_.max_leaf_size) split = split_median(begin, end, axis);
      }
    }

    if (split == end || split == begin) {
      bvh_.nodes[index] = BvhNode{bounds, std::uint32_t(begin - primitives_.begin()), std::uint16_t(count), 0, 1};
      return;
    }
    const auto first = std::uint32_t(bvh_.nodes.size());
    bvh_.nodes.resize(bvh_.nodes.size() + 2);
    bvh_.nodes[index] = BvhNode{bounds, first, 0, std::uint8_t(axis), 0};
    build_node(first, begin, split, depth + 1);
    build_node(first + 1, split, end, depth + 1);
  }

  std::vector<BuildPrimitive> primitives_;
  BvhBuildOptions options_;
  Bvh bvh_;
};

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& primitive_bounds, const BvhBuildOptions& options) {
  if (options.max_leaf_size < 1 || options.max_leaf_size > 255)
    throw UsageError("BVH leaf size must be in [1, 255], got " + std::to_string(options.max_leaf_size));
  std::vector<BuildPrimitive> primitives;
  primitives.reserve(primitive_bounds.size());
  for (size_t i = 0; i < primitive_bounds.size(); ++i)
    primitives.push_back({primitive_bounds[i], primitive_bounds[i].centroid(), std::uint32_t(i)});
  return Builder(std::move(primitives), options).build();
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
