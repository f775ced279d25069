#pragma once
// What the BVH builder (bvh.cpp) and its three split tasks (bvh_split.cpp) share: the primitives as
// the build sees them, their extent, and the splits' declarations. Private to this stage: the
// rest of the framework sees build_bvh (bvh.h) alone.

#include "03-acceleration/bvh.h"
#include "common/float4.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace rt::bvh_build {

// The order of the fields matters: four floats from the box's low corner or from its high one stay
// inside the primitive and are all numbers (Box4 loads them so).
struct BuildPrimitive {
  Aabb bounds;
  Vec3 centroid;
  std::uint32_t index;
};
static_assert(offsetof(BuildPrimitive, centroid) == sizeof(Aabb), "Box4::expand reads past bounds.hi");
using BuildPrimitives = std::vector<BuildPrimitive, CacheLineAllocator<BuildPrimitive>>;
using Iterator = BuildPrimitives::iterator;

// A box in two SSE registers, for the build's inner loops: growing it by a primitive's box is one
// minimum and one maximum for all three axes (BuildPrimitive's layout lets each corner load as
// four floats; the fourth lane is never read back). With an Aabb's three floats a corner, the
// SAH's binning loop was six scalar instructions per bin, and most of the build. Box4::empty()
// makes the empty box; the members have no initializers, because with them GCC set up each
// node's 48 bins element by element, and the 10^6-triangle build took 7 % longer.
struct Box4 {
  Float4 lo, hi;

  static Box4 empty() { return Box4{broadcast(kInfinity), broadcast(-kInfinity)}; }

  // As Aabb::expand (glm::min and glm::max), a NaN coordinate leaves the box as it was.
  void expand(Float4 lo_corner, Float4 hi_corner) {
    lo = min4(lo_corner, lo);
    hi = max4(hi_corner, hi);
  }
  void expand(Float4 point) { expand(point, point); }
  void expand(const Box4& b) { expand(b.lo, b.hi); }
  void expand(const BuildPrimitive& p) { expand(load4(&p.bounds.lo.x), load4(&p.bounds.hi.x)); }
  // Aabb::half_area's arithmetic, the three products in one multiplication.
  float half_area() const {
    if ((lane_mask(lo <= hi) & 7u) != 7u) return 0.0f;  // empty
    const Float4 e = hi - lo;
    const Float4 products = e * Float4{e[1], e[2], e[0], 0.0f};  // (x y, y z, z x)
    return products[0] + products[1] + products[2];
  }
  Aabb aabb() const { return Aabb{Vec3(lo[0], lo[1], lo[2]), Vec3(hi[0], hi[1], hi[2])}; }
};

// What a node needs to know of its primitives before it splits them: the box around them (the
// node's box) and the box around their centroids (what the splits divide).
struct Extent {
  Box4 bounds = Box4::empty(), centroids = Box4::empty();
  void add(const BuildPrimitive& p) {
    const Float4 lo = load4(&p.bounds.lo.x), hi = load4(&p.bounds.hi.x);
    bounds.expand(lo, hi);
    centroids.expand(0.5f * (lo + hi));  // Aabb::centroid, lane for lane: p.centroid
  }
};

inline Extent measure(Iterator begin, Iterator end) {
  Extent extent;
  for (Iterator p = begin; p != end; ++p) extent.add(*p);
  return extent;
}

// The two sides of a split node: where the second one begins, and each one's extent.
struct Split {
  Iterator at;
  Extent left, right;
};

// The three splits, each a task stated where bvh_split.cpp defines it. The builder calls them on a
// node of at least two primitives whose centroids are not all equal along `axis` (it halves those
// itself).
Iterator split_median(Iterator begin, Iterator end, int axis);
Iterator split_middle(Iterator begin, Iterator end, int axis, const Aabb& centroid_bounds);
std::optional<Split> split_sah(Iterator begin, Iterator end, const Aabb& node_bounds, const Aabb& centroid_bounds,
                               const BvhBuildOptions& options);

}  // namespace rt::bvh_build
