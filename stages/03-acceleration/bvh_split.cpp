// The three ways to split a node of the BVH (docs/stage3.md): the lecture's median and middle
// splits and the binned surface area heuristic. The builder that calls them is bvh.cpp; what
// they share with it is bvh_build.h.
#include "03-acceleration/bvh_build.h"
#include "common/task.h"

#include <algorithm>
#include <array>
#include <bit>

namespace rt::bvh_build {
namespace {

// The SAH's bins along one axis, and a bit per bin that says which bins hold primitives: the sweep
// then visits those alone (see split_sah), and most nodes of a tree hold only a few primitives.
struct SahBins {
  static constexpr int kBins = BvhBuildOptions::kSahBins;
  std::array<Box4, kBins> box;
  std::array<int, kBins> count{};
  unsigned used = 0;

  SahBins() { box.fill(Box4::empty()); }
  void add(int bin, const BuildPrimitive& p) {
    box[size_t(bin)].expand(p);
    ++count[size_t(bin)];
    used |= 1u << bin;
  }
  // The bins that hold primitives, in order, into `list`; returns how many there are.
  int used_bins(std::array<int, kBins>& list) const {
    int n = 0;
    for (unsigned m = used; m != 0; m &= m - 1) list[size_t(n++)] = std::countr_zero(m);
    return n;
  }
};

// std::partition that measures both sides on the way: each primitive is read once, where measuring
// the two children in a pass of their own would read them all again (a third of the SAH build's
// passes over the primitives).
template <class Predicate>
Split partition_measured(Iterator begin, Iterator end, Predicate goes_left) {
  Split split{};
  Iterator i = begin, j = end;
  while (true) {
    while (i != j && goes_left(*i)) split.left.add(*i++);
    while (i != j && !goes_left(*(j - 1))) split.right.add(*--j);
    if (i == j) break;
    // *i belongs right and *(j - 1) left: swap them.
    --j;
    std::iter_swap(i, j);
    split.left.add(*i++);
    split.right.add(*j);
  }
  split.at = i;
  return split;
}

}  // namespace

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
// Returns no split when none is cheaper than a leaf and the node is small enough to be one, or
// when the best boundary leaves one side empty; otherwise partitions [begin, end) at the best
// boundary.
std::optional<Split> split_sah(Iterator begin, Iterator end, const Aabb& node_bounds, const Aabb& centroid_bounds,
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
  // bin_of for all three axes at once, lane by lane the same arithmetic (the centroid recomputed
  // from the box, as BuildPrimitive::centroid was, so that all four lanes hold numbers).
  const Float4 lo4{centroid_bounds.lo.x, centroid_bounds.lo.y, centroid_bounds.lo.z, 0.0f};
  const Float4 scale4{scale.x, scale.y, scale.z, 0.0f};
  auto bins_of = [&](const BuildPrimitive& p) {
    const Float4 centroid = 0.5f * (load4(&p.bounds.lo.x) + load4(&p.bounds.hi.x));
    const Float4 bin = (centroid - lo4) * scale4;
    return __builtin_convertvector(bin >= Float4{} ? min4(bin, broadcast(float(kBins - 1))) : Float4{}, Int4);
  };
  float best_area_count = kInfinity;
  int best_axis = -1, best_boundary = 0;
  // BEGIN TASK stage3.bvh.sah_split
  // One pass over the primitives fills the bins of all three axes: near the root the primitives
  // do not fit in the cache, and reading them once instead of three times is most of the build.
  std::array<SahBins, 3> bins;  // [axis]
  for (Iterator p = begin; p != end; ++p) {
    const Int4 bin = bins_of(*p);
    for (int axis = 0; axis < 3; ++axis) bins[size_t(axis)].add(bin[axis], *p);
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!(extent[axis] > 0.0f)) continue;  // all centroids in one plane: no bins
    const auto& bounds = bins[size_t(axis)].box;
    const auto& count = bins[size_t(axis)].count;
    // Only a bin that holds primitives ends a boundary of its own: after an empty bin both sides
    // are those after the bin before it, at the same cost. A node of a few primitives so sweeps a
    // few bins, not kBins (the first and the last bin always hold the extreme centroids).
    std::array<int, kBins> used;
    const int n = bins[size_t(axis)].used_bins(used);
    // area_count[k]: A N of the used bins [0, k] plus A N of the used bins [k + 1, n), for the
    // boundary after the k-th used bin: one sweep from below, one from above.
    std::array<float, kBins - 1> area_count;
    Box4 below = Box4::empty(), above = Box4::empty();
    int count_below = 0, count_above = 0;
    for (int k = 0; k + 1 < n; ++k) {
      const auto i = size_t(used[size_t(k)]);
      below.expand(bounds[i]);
      count_below += count[i];
      area_count[size_t(k)] = below.half_area() * float(count_below);
    }
    for (int k = n - 1; k >= 1; --k) {
      const auto i = size_t(used[size_t(k)]);
      above.expand(bounds[i]);
      count_above += count[i];
      area_count[size_t(k - 1)] += above.half_area() * float(count_above);
    }
    for (int k = 0; k + 1 < n; ++k)
      if (area_count[size_t(k)] < best_area_count) {
        best_area_count = area_count[size_t(k)];
        best_axis = axis;
        best_boundary = used[size_t(k)];
      }
  }
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.sah_split");
  // (void)bin_of, (void)bins_of;
  // const Iterator median = split_median(begin, end, centroid_bounds.longest_axis());  // the lecture's split until this one is done
  // return Split{median, measure(begin, median), measure(median, end)};
  // END TASK
  if (best_axis < 0) return std::nullopt;
  const float area = node_bounds.half_area();
  const float split_cost = BvhBuildOptions::kTraversalCost +
                           BvhBuildOptions::kIntersectionCost * (area > 0.0f ? best_area_count / area : 0.0f);
  const auto count = int(end - begin);
  if (count <= options.max_leaf_size && leaf_cost(count, options) <= split_cost) return std::nullopt;
  Split split =
      partition_measured(begin, end, [&](const BuildPrimitive& p) { return bin_of(p, best_axis) <= best_boundary; });
  if (split.at == begin || split.at == end) return std::nullopt;
  return split;
}

}  // namespace rt::bvh_build
