// Stage 3: the slab test and the BVH's two traversal loops, in one file so that the loops compile
// the slab test in (aabb.h and bvh.h give the contracts). The primitive test comes from the
// caller through a FunctionRef: one indirect call per primitive, against the box tests' none.
#include "03-acceleration/bvh.h"
#include "common/task.h"

namespace rt {

std::optional<float> intersect_aabb(const Aabb& box, const RayInverse& ray, Interval range) {
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

[[gnu::flatten]] std::optional<std::pair<float, std::uint32_t>> bvh_closest_hit(
    const Bvh& bvh, const Ray& ray, Interval range, FunctionRef<std::optional<float>(std::uint32_t, Interval)> hit_primitive) {
  std::optional<std::pair<float, std::uint32_t>> closest;
  // BEGIN TASK stage3.bvh.closest_hit
  const RayInverse inverse(ray);
  if (!intersect_aabb(bvh.nodes[0].bounds, inverse, range)) return closest;
  // Each entry: a node whose box the ray enters at t (known when it was pushed), so that a node
  // farther than the nearest hit found since is dropped without reading it.
  struct Entry {
    std::uint32_t node;
    float t;
  };
  Entry stack[Bvh::kStackSize];
  int stack_size = 0;
  std::uint32_t current = 0;
  while (true) {
    const BvhNode& node = bvh.nodes[current];
    if (node.is_leaf) {
      for (std::uint32_t slot = node.offset; slot < node.offset + node.count; ++slot)
        if (const std::optional<float> t = hit_primitive(slot, range)) {
          closest = {*t, slot};
          range.max = *t;
        }
    } else {
      // Test both children's boxes here, go on into the nearer one, keep the other for later.
      const std::uint32_t first = node.offset, second = node.offset + 1;
      const std::optional<float> t_first = intersect_aabb(bvh.nodes[first].bounds, inverse, range);
      const std::optional<float> t_second = intersect_aabb(bvh.nodes[second].bounds, inverse, range);
      if (t_first && t_second) {
        const bool first_is_nearer = *t_first <= *t_second;
        stack[stack_size++] = first_is_nearer ? Entry{second, *t_second} : Entry{first, *t_first};
        current = first_is_nearer ? first : second;
        continue;
      }
      if (t_first || t_second) {
        current = t_first ? first : second;
        continue;
      }
    }
    // Resume with the nearest pending node that may still hold something nearer than `closest`.
    while (stack_size > 0 && stack[stack_size - 1].t > range.max) --stack_size;
    if (stack_size == 0) break;
    current = stack[--stack_size].node;
  }
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.closest_hit");
  // (void)bvh;
  // for (std::uint32_t slot = 0; slot < std::uint32_t(bvh.order.size()); ++slot)
  //   if (const std::optional<float> t = hit_primitive(slot, range)) {  // every primitive: slow but right
  //     closest = {*t, slot};
  //     range.max = *t;
  //   }
  // (void)ray;
  // END TASK
  return closest;
}

[[gnu::flatten]] bool bvh_any_hit(const Bvh& bvh, const Ray& ray, Interval range, FunctionRef<bool(std::uint32_t, Interval)> hits_primitive) {
  // BEGIN TASK stage3.bvh.any_hit
  const RayInverse inverse(ray);
  if (!intersect_aabb(bvh.nodes[0].bounds, inverse, range)) return false;
  std::uint32_t stack[Bvh::kStackSize];
  int stack_size = 0;
  std::uint32_t current = 0;
  while (true) {
    const BvhNode& node = bvh.nodes[current];
    if (node.is_leaf) {
      for (std::uint32_t slot = node.offset; slot < node.offset + node.count; ++slot)
        if (hits_primitive(slot, range)) return true;
    } else {
      // Any order will do: the first occluder ends the walk.
      const std::uint32_t first = node.offset, second = node.offset + 1;
      const bool enter_first = intersect_aabb(bvh.nodes[first].bounds, inverse, range).has_value();
      const bool enter_second = intersect_aabb(bvh.nodes[second].bounds, inverse, range).has_value();
      if (enter_first && enter_second) stack[stack_size++] = second;
      if (enter_first || enter_second) {
        current = enter_first ? first : second;
        continue;
      }
    }
    if (stack_size == 0) return false;
    current = stack[--stack_size];
  }
  // PLACEHOLDER
  // report_unfinished_task("stage3.bvh.any_hit");
  // (void)ray;
  // for (std::uint32_t slot = 0; slot < std::uint32_t(bvh.order.size()); ++slot)
  //   if (hits_primitive(slot, range)) return true;
  // return false;
  // END TASK
}

}  // namespace rt
