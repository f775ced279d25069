// Stage 3, beyond the lecture: a 4-wide BVH, collapsed from the binary one. Each node holds the
// boxes of up to four children, stored axis by axis, so that one loop tests all four with the
// same instructions on four lanes (the compiler turns it into SSE). The tree is half as deep, a
// visit reads two cache lines for four boxes, and a ray that enters many overlapping boxes (a
// room, where every wall's box spans the scene) pays far less per box. Wide BVHs collapsed from
// binary ones: Dammertz, Hanika & Keller, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray
// Tracing of Incoherent Rays", EGSR 2008; Wald, Benthin & Boulos, "Getting Rid of Packets", IRT 2008.
#pragma once

#include "03-acceleration/bvh.h"
#include "common/float4.h"

namespace rt {

struct alignas(64) WideBvhNode {
  static constexpr int kWidth = 4;
  // [side][axis][child], side 0 the low corner and 1 the high one. An unused child has an empty
  // box (low = +inf, high = -inf), which the slab test never hits. The side is an index so that
  // a ray picks its near and far planes by its direction's signs without a branch.
  float bounds[2][3][kWidth];
  // Interior child: its node index, and count 0. Leaf child: its first slot in Bvh::order and its
  // number of primitives (an aggregate may store its leaves its own way and change both, keeping
  // count nonzero). Unused child: 0 and 0.
  std::uint32_t child[kWidth];
  std::uint32_t count[kWidth];
};
static_assert(sizeof(WideBvhNode) == 128, "WideBvhNode must stay two cache lines");

struct WideBvh {
  std::vector<WideBvhNode, CacheLineAllocator<WideBvhNode>> nodes;  // nodes[0] is the root
  Aabb bounds;  // the whole tree's box (the traversal tests the root's four boxes instead)
  // Each visit pushes at most 3 entries, and the tree is no deeper than the binary one.
  static constexpr int kStackSize = 3 * Bvh::kStackSize;
};

// Collapses a binary BVH: starting from a node's two children, the child with the largest surface
// area is replaced by its own two children until there are four (or only leaves are left). The
// leaves and the primitive order (Bvh::order) are the binary tree's.
WideBvh collapse_to_wide(const Bvh& bvh);

// The slab test (stage3.aabb.slab) on a node's four boxes at once. Returns a bit per child, set
// when the ray meets its box within `range`; t_enter[i] is child i's entry distance.
[[gnu::always_inline]] inline unsigned intersect_wide_node(const WideBvhNode& node, const RayInverse& ray, Interval range,
                                                           float* __restrict t_enter) {
  // The sign of 1/d picks each axis's near and far plane for all four boxes alike: the near side
  // is the high one (1) where d < 0. Indexing, not `negative ? hi : lo`, which GCC compiles to a
  // jump per axis that random directions mispredict half the time.
  const Float4 near_x = load4(node.bounds[ray.negative[0]][0]), far_x = load4(node.bounds[!ray.negative[0]][0]);
  const Float4 near_y = load4(node.bounds[ray.negative[1]][1]), far_y = load4(node.bounds[!ray.negative[1]][1]);
  const Float4 near_z = load4(node.bounds[ray.negative[2]][2]), far_z = load4(node.bounds[!ray.negative[2]][2]);
  const Float4 near_tx = (near_x - ray.origin.x) * ray.inv_direction.x;
  const Float4 near_ty = (near_y - ray.origin.y) * ray.inv_direction.y;
  const Float4 near_tz = (near_z - ray.origin.z) * ray.inv_direction.z;
  const Float4 far_tx = (far_x - ray.origin.x) * ray.inv_direction.x * kSlabRounding;
  const Float4 far_ty = (far_y - ray.origin.y) * ray.inv_direction.y * kSlabRounding;
  const Float4 far_tz = (far_z - ray.origin.z) * ray.inv_direction.z * kSlabRounding;
  // As in intersect_aabb: "new > old ? new : old", so a NaN lane (0 * inf) leaves the interval.
  Float4 enter = Float4{} + range.min, exit = Float4{} + range.max;
  enter = near_tx > enter ? near_tx : enter;
  enter = near_ty > enter ? near_ty : enter;
  enter = near_tz > enter ? near_tz : enter;
  exit = far_tx < exit ? far_tx : exit;
  exit = far_ty < exit ? far_ty : exit;
  exit = far_tz < exit ? far_tz : exit;
  std::memcpy(t_enter, &enter, sizeof enter);
  return lane_mask(enter <= exit);
}

// The contracts of bvh_closest_hit and bvh_any_hit (bvh.h), over the wide tree, a leaf at a time:
// the traversal hands each leaf it enters to the caller's test, as the node holds it (child and
// count; an aggregate may store a leaf its own way, as PackedWideBvh stores triangles in packs),
//   hit_leaf(child, count, range) -> std::optional<float>: the nearest t strictly inside `range`
//                                    among the leaf's primitives (the caller notes which);
//   hits_leaf(child, count, range) -> bool: whether any of them is hit inside `range`.
// The closest-hit loop is always inlined into its caller, so that the hit it finds stays in
// registers: returned from a call, an optional hit goes through memory in pieces and comes back
// in one load that the stores cannot forward (a stall per query; docs/stage5.md, the speed ladder).
template <class HitLeaf>
[[gnu::always_inline]] inline std::optional<float> wide_bvh_closest_hit(const WideBvh& bvh, const Ray& ray,
                                                                        Interval range, HitLeaf&& hit_leaf);
template <class HitsLeaf>
bool wide_bvh_any_hit(const WideBvh& bvh, const Ray& ray, Interval range, HitsLeaf&& hits_leaf);

// A leaf test made of a test per primitive slot, for leaves as collapse_to_wide leaves them (slots
// child ... child + count - 1): hit_primitive(slot, range) -> std::optional<float>, and the slot
// of the nearest hit is written to `nearest_slot`. The test refers to both; they must outlive it.
template <class HitPrimitive>
[[gnu::always_inline]] inline auto slot_by_slot(HitPrimitive&& hit_primitive, std::uint32_t& nearest_slot) {
  return [&hit_primitive, &nearest_slot](std::uint32_t child, std::uint32_t count, Interval range)
             __attribute__((always_inline)) {
    std::optional<float> nearest;
    for (std::uint32_t slot = child; slot < child + count; ++slot)
      if (const std::optional<float> t = hit_primitive(slot, range)) {
        nearest = t;
        nearest_slot = slot;
        range.max = *t;
      }
    return nearest;
  };
}

// Whether a ray can be traced at all. The slab test ignores a NaN operand (intersect_aabb), so a ray
// with a NaN in it would "enter" every box, the empty slots of a node too, whose child is no node:
// such a ray (a lens at 10^8 units, a hit record gone wrong upstream) meets nothing instead.
// x * 0 is 0 for every finite x and NaN for a NaN or an infinity: the six coordinates in two
// overlapping loads of four (the ray's 24 bytes), one compare; six scalar tests cost the Cornell
// box 2.4 % more instructions per path (callgrind, 32 x 32 pixels at 8 and 32 spp), this 0.6 %.
[[gnu::always_inline]] inline bool traversable(const Ray& ray) {
  static_assert(sizeof(Ray) == 6 * sizeof(float), "a ray is its origin and direction, packed");
  const float* coordinates = &ray.origin.x;
  const Float4 zero = load4(coordinates) * 0.0f + load4(coordinates + 2) * 0.0f;
  return lane_mask(zero == Float4{}) == 0xF;
}

// A stack entry: a child of some node (interior when count == 0) and where the ray enters its box.
struct WideBvhEntry {
  std::uint32_t child, count;
  float t;
};

template <class HitLeaf>
std::optional<float> wide_bvh_closest_hit(const WideBvh& bvh, const Ray& ray, Interval range, HitLeaf&& hit_leaf) {
  std::optional<float> closest;
  // No test of the whole tree's box first: the root's four boxes are tested next anyway, and in a
  // closed scene (a room) every ray is inside it.
  if (bvh.nodes.empty() || !traversable(ray)) return closest;
  const RayInverse inverse(ray);
  WideBvhEntry stack[WideBvh::kStackSize];
  int stack_size = 0;
  WideBvhEntry current{0, 0, range.min};
  while (true) {
    if (current.count == 0) {
      const WideBvhNode& node = bvh.nodes[current.child];
      float t[4];
      unsigned hits = intersect_wide_node(node, inverse, range, t);
      if (hits != 0) {
        // The children the ray enters, nearest first (insertion sort of at most four), taken
        // bit by bit from the mask: the usual case, one or two children, costs one or two steps.
        WideBvhEntry entered[4];
        int n = 0;
        for (; hits != 0; hits &= hits - 1) {
          const int i = __builtin_ctz(hits);
          int k = n++;
          for (; k > 0 && entered[k - 1].t > t[i]; --k) entered[k] = entered[k - 1];
          entered[k] = WideBvhEntry{node.child[i], node.count[i], t[i]};
        }
        for (int k = n - 1; k >= 1; --k) stack[stack_size++] = entered[k];
        current = entered[0];
        continue;
      }
    } else if (const std::optional<float> t = hit_leaf(current.child, current.count, range)) {
      closest = t;
      range.max = *t;
    }
    while (stack_size > 0 && stack[stack_size - 1].t > range.max) --stack_size;
    if (stack_size == 0) break;
    current = stack[--stack_size];
  }
  return closest;
}

template <class HitsLeaf>
bool wide_bvh_any_hit(const WideBvh& bvh, const Ray& ray, Interval range, HitsLeaf&& hits_leaf) {
  if (bvh.nodes.empty() || !traversable(ray)) return false;
  const RayInverse inverse(ray);
  WideBvhEntry stack[WideBvh::kStackSize];
  int stack_size = 0;
  WideBvhEntry current{0, 0, 0.0f};
  while (true) {
    if (current.count == 0) {
      const WideBvhNode& node = bvh.nodes[current.child];
      float t[4];
      for (unsigned hits = intersect_wide_node(node, inverse, range, t); hits != 0; hits &= hits - 1) {
        const int i = __builtin_ctz(hits);
        stack[stack_size++] = WideBvhEntry{node.child[i], node.count[i], t[i]};
      }
    } else if (hits_leaf(current.child, current.count, range)) {
      return true;
    }
    if (stack_size == 0) return false;
    current = stack[--stack_size];
  }
}

}  // namespace rt
