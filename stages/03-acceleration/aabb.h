// Stage 3: the lecture's slab test, a ray against an axis-aligned bounding box (common/aabb.h).
#pragma once

#include "common/aabb.h"
#include "common/interval.h"
#include "common/ray.h"

#include <optional>

namespace rt {

// What the slab test needs of a ray, computed once per ray: 1/d per axis. A zero component gives
// +-infinity (IEEE 754), which is exactly right: that slab either contains the origin for every t
// or for none.
// 1 + 2 gamma_3 (PBR 4th ed. section 6.8.2): the relative error of (plane - o) * (1/d) is at most
// gamma_3, for the near and the far value alike.
inline constexpr float kSlabRounding = 1.0f + 2.0f * (3.0f * 0x1p-24f / (1.0f - 3.0f * 0x1p-24f));

struct RayInverse {
  Vec3 origin;
  Vec3 inv_direction;
  bool negative[3];  // inv_direction < 0 per axis: which plane of each slab is entered first
  explicit RayInverse(const Ray& ray)
      : origin(ray.origin),
        inv_direction(1.0f / ray.direction),
        negative{inv_direction.x < 0.0f, inv_direction.y < 0.0f, inv_direction.z < 0.0f} {}
};

// Task stage3.aabb.slab. The lecture's slab test (Kay & Kajiya 1986): per axis the ray is between
// the two planes for t in [(lo - o) / d, (hi - o) / d] (swapped when d < 0); the ray is in the box
// for the intersection of the three intervals and `range`:
//     t_enter = max(range.min, t_min per axis),  t_exit = min(range.max, t_max per axis),
// a hit iff t_enter <= t_exit. Boundaries count (a flat box, a ray grazing a face), because a
// false hit only costs time while a false miss loses geometry. Corner cases, each tested:
//  - d = +0 or -0: 1/d = +-inf; from an origin between the planes the interval is (-inf, inf).
//  - an origin exactly ON a plane with d = 0 gives 0 * inf = NaN. The max/min are written so that a
//    NaN operand is ignored (Williams et al., "An Efficient and Robust Ray-Box Intersection
//    Algorithm", JGT 10(1), 2005); that slab then does not cut the interval, which is inclusive.
//  - rounding can make t_enter exceed t_exit by an ulp for a box the ray does cross; t_exit is
//    enlarged by 1 + 2 gamma_3 (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013).
// Returns the entry distance (clamped to range.min) on a hit. Defined in bvh_traversal.cpp, beside
// the traversal loops that call it at every node they visit: in one file the compiler builds it
// into them (a call per box test cost the binary BVH 25 % of its rays per second on the bunny).
std::optional<float> intersect_aabb(const Aabb& box, const RayInverse& ray, Interval range);

}  // namespace rt
