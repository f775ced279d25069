// Stage 3: the lecture's slab test, a ray against an axis-aligned bounding box (common/aabb.h).
#pragma once

#include "common/aabb.h"
#include "common/interval.h"
#include "common/task.h"
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
// Returns the entry distance (clamped to range.min) on a hit. Always inlined: the BVH calls it for
// every node it visits, it is most of a traversal's time, and left to itself GCC stops inlining it
// once the traversal around it grows (measured: the binary BVH lost 25 % of its rays per second on
// the bunny when the primitive test beside it got a kind switch).
[[gnu::always_inline]] inline std::optional<float> intersect_aabb(const Aabb& box, const RayInverse& ray, Interval range) {
  // BEGIN TASK stage3.aabb.slab
  float t_enter = range.min, t_exit = range.max;
  for (int axis = 0; axis < 3; ++axis) {
    // Which plane is entered first follows from the sign of 1/d, not from comparing the two t:
    // for d = -0, 1/d = -inf says "negative" where d < 0 would not, and an empty box (lo > hi)
    // stays empty instead of being turned inside out by a swap (Williams et al. 2005).
    const float near_plane = ray.negative[axis] ? box.hi[axis] : box.lo[axis];
    const float far_plane = ray.negative[axis] ? box.lo[axis] : box.hi[axis];
    const float t_near = (near_plane - ray.origin[axis]) * ray.inv_direction[axis];
    const float t_far = (far_plane - ray.origin[axis]) * ray.inv_direction[axis] * kSlabRounding;
    // Written as "new > old ? new : old" so that a NaN (0 * inf: an origin on a plane the ray runs
    // parallel to) leaves the interval as it was: the ray is on the boundary, which counts.
    t_enter = t_near > t_enter ? t_near : t_enter;
    t_exit = t_far < t_exit ? t_far : t_exit;
  }
  if (t_enter > t_exit) return std::nullopt;
  return t_enter;
  // PLACEHOLDER
  // report_unfinished_task("stage3.aabb.slab");
  // (void)box, (void)ray;
  // return range.min;  // every box is hit: correct, only slow
  // END TASK
}

}  // namespace rt
