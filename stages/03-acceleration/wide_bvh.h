// Stage 3, beyond the lecture: a 4-wide BVH, collapsed from the binary one. Each node holds the
// boxes of up to four children, stored axis by axis, so that one loop tests all four with the
// same instructions on four lanes (the compiler turns it into SSE). The tree is half as deep, a
// visit reads two cache lines for four boxes, and a ray that enters many overlapping boxes (a
// room, where every wall's box spans the scene) pays far less per box. Wide BVHs collapsed from
// binary ones: Dammertz, Hanika & Keller, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray
// Tracing of Incoherent Rays", EGSR 2008; Wald, Benthin & Boulos, "Getting Rid of Packets", IRT 2008.
#pragma once

#include "03-acceleration/bvh.h"

namespace rt {

struct alignas(64) WideBvhNode {
  static constexpr int kWidth = 4;
  float lo[3][kWidth];  // [axis][child]; an unused child has an empty box (lo = +inf, hi = -inf),
  float hi[3][kWidth];  // which the slab test never hits
  std::uint32_t child[kWidth];  // interior child: its node index; leaf child: its first slot in Bvh::order
  std::uint32_t count[kWidth];  // leaf child: its number of primitives; interior or unused child: 0
};
static_assert(sizeof(WideBvhNode) == 128, "WideBvhNode must stay two cache lines");

struct WideBvh {
  std::vector<WideBvhNode, CacheLineAllocator<WideBvhNode>> nodes;  // nodes[0] is the root
  Aabb bounds;  // the whole tree's box, tested once per ray
  // Each visit pushes at most 3 entries, and the tree is no deeper than the binary one.
  static constexpr int kStackSize = 3 * Bvh::kStackSize;
};

// Collapses a binary BVH: starting from a node's two children, the child with the largest surface
// area is replaced by its own two children until there are four (or only leaves are left). The
// leaves and the primitive order (Bvh::order) are the binary tree's.
WideBvh collapse_to_wide(const Bvh& bvh);

// The slab test (stage3.aabb.slab) on a node's four boxes at once. t_enter[i] is child i's entry
// distance; hit[i] is nonzero when the ray meets box i within `range`.
inline void intersect_wide_node(const WideBvhNode& node, const RayInverse& ray, Interval range, float* __restrict t_enter,
                                int* __restrict hit) {
  // The sign of 1/d picks each axis's near and far plane for all four boxes alike.
  const float* near_x = ray.negative[0] ? node.hi[0] : node.lo[0];
  const float* far_x = ray.negative[0] ? node.lo[0] : node.hi[0];
  const float* near_y = ray.negative[1] ? node.hi[1] : node.lo[1];
  const float* far_y = ray.negative[1] ? node.lo[1] : node.hi[1];
  const float* near_z = ray.negative[2] ? node.hi[2] : node.lo[2];
  const float* far_z = ray.negative[2] ? node.lo[2] : node.hi[2];
  const float ox = ray.origin.x, oy = ray.origin.y, oz = ray.origin.z;
  const float ix = ray.inv_direction.x, iy = ray.inv_direction.y, iz = ray.inv_direction.z;
  // Written lane by lane, with NaN-ignoring max/min as in intersect_aabb; the compiler runs the
  // four lanes as one SSE instruction each (once it has unrolled the loop it no longer does, hence
  // the pragma).
#pragma GCC unroll 1
  for (int i = 0; i < WideBvhNode::kWidth; ++i) {
    const float near_tx = (near_x[i] - ox) * ix, far_tx = (far_x[i] - ox) * ix * kSlabRounding;
    const float near_ty = (near_y[i] - oy) * iy, far_ty = (far_y[i] - oy) * iy * kSlabRounding;
    const float near_tz = (near_z[i] - oz) * iz, far_tz = (far_z[i] - oz) * iz * kSlabRounding;
    float enter = range.min, exit = range.max;
    enter = near_tx > enter ? near_tx : enter;
    enter = near_ty > enter ? near_ty : enter;
    enter = near_tz > enter ? near_tz : enter;
    exit = far_tx < exit ? far_tx : exit;
    exit = far_ty < exit ? far_ty : exit;
    exit = far_tz < exit ? far_tz : exit;
    t_enter[i] = enter;
    hit[i] = enter <= exit ? -1 : 0;
  }
}

// The contracts of bvh_closest_hit and bvh_any_hit (bvh.h), over the wide tree.
template <class HitPrimitive>
std::optional<std::pair<float, std::uint32_t>> wide_bvh_closest_hit(const WideBvh& bvh, const Ray& ray,
                                                                     Interval range, HitPrimitive&& hit_primitive);
template <class HitsPrimitive>
bool wide_bvh_any_hit(const WideBvh& bvh, const Ray& ray, Interval range, HitsPrimitive&& hits_primitive);

// A stack entry: a child of some node (interior when count == 0) and where the ray enters its box.
struct WideBvhEntry {
  std::uint32_t child, count;
  float t;
};

template <class HitPrimitive>
std::optional<std::pair<float, std::uint32_t>> wide_bvh_closest_hit(const WideBvh& bvh, const Ray& ray,
                                                                     Interval range, HitPrimitive&& hit_primitive) {
  std::optional<std::pair<float, std::uint32_t>> closest;
  const RayInverse inverse(ray);
  const std::optional<float> t_root = intersect_aabb(bvh.bounds, inverse, range);
  if (!t_root || bvh.nodes.empty()) return closest;
  WideBvhEntry stack[WideBvh::kStackSize];
  int stack_size = 0;
  WideBvhEntry current{0, 0, *t_root};
  while (true) {
    if (current.count == 0) {
      const WideBvhNode& node = bvh.nodes[current.child];
      float t[4];
      int hit[4];
      intersect_wide_node(node, inverse, range, t, hit);
      // The children the ray enters, nearest first (insertion sort of at most four).
      WideBvhEntry entered[4];
      int n = 0;
      for (int i = 0; i < WideBvhNode::kWidth; ++i) {
        if (!hit[i]) continue;
        int k = n++;
        for (; k > 0 && entered[k - 1].t > t[i]; --k) entered[k] = entered[k - 1];
        entered[k] = WideBvhEntry{node.child[i], node.count[i], t[i]};
      }
      if (n > 0) {
        for (int k = n - 1; k >= 1; --k) stack[stack_size++] = entered[k];
        current = entered[0];
        continue;
      }
    } else {
      for (std::uint32_t slot = current.child; slot < current.child + current.count; ++slot)
        if (const std::optional<float> t = hit_primitive(slot, range)) {
          closest = {*t, slot};
          range.max = *t;
        }
    }
    while (stack_size > 0 && stack[stack_size - 1].t > range.max) --stack_size;
    if (stack_size == 0) break;
    current = stack[--stack_size];
  }
  return closest;
}

template <class HitsPrimitive>
bool wide_bvh_any_hit(const WideBvh& bvh, const Ray& ray, Interval range, HitsPrimitive&& hits_primitive) {
  const RayInverse inverse(ray);
  if (!intersect_aabb(bvh.bounds, inverse, range) || bvh.nodes.empty()) return false;
  WideBvhEntry stack[WideBvh::kStackSize];
  int stack_size = 0;
  WideBvhEntry current{0, 0, 0.0f};
  while (true) {
    if (current.count == 0) {
      const WideBvhNode& node = bvh.nodes[current.child];
      float t[4];
      int hit[4];
      intersect_wide_node(node, inverse, range, t, hit);
      for (int i = 0; i < WideBvhNode::kWidth; ++i)
        if (hit[i]) stack[stack_size++] = WideBvhEntry{node.child[i], node.count[i], t[i]};
    } else {
      for (std::uint32_t slot = current.child; slot < current.child + current.count; ++slot)
        if (hits_primitive(slot, range)) return true;
    }
    if (stack_size == 0) return false;
    current = stack[--stack_size];
  }
}

}  // namespace rt
