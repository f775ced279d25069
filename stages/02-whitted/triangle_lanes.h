// Stage 2, beyond the lecture: the watertight test (triangle_intersection.h) with a triangle's
// three corners in three lanes of one SSE register (common/float4.h). The scalar test does the
// same arithmetic three times, once per corner: move the corner to the ray's origin, shear it, and
// take the edge function opposite it. Here each of those lines is one instruction for all three
// corners, and the permutation of the axes becomes the choice of which rows to load: the corners
// are stored axis by axis (TriangleCorners), so the ray's kx, ky and kz index whole rows (as stage
// 3's 4-wide node is indexed by the signs of the ray's direction).
//
// Every lane does, operation for operation, what the scalar test does for its corner, and the
// sums over the lanes are added in the scalar test's order, so the answer is the scalar test's
// bit for bit (tests/stage2/triangle_lanes_test.cpp checks it). Measured in docs/stage5.md and
// docs/stage3.md (the speed ladders).
#pragma once

#include "02-whitted/triangle_intersection.h"
#include "common/float4.h"

namespace rt {

// A triangle's corners stored axis by axis: coordinate[axis][corner], then one float of padding,
// 40 bytes. A row is loaded as four floats at once: lane 3 of rows 0 and 1 is the next row's first
// value, of row 2 the padding, and lane 3 is never used.
struct TriangleCorners {
  float coordinate[3][3];
  float padding = 0.0f;

  TriangleCorners() = default;
  TriangleCorners(Vec3 v0, Vec3 v1, Vec3 v2)
      : coordinate{{v0.x, v1.x, v2.x}, {v0.y, v1.y, v2.y}, {v0.z, v1.z, v2.z}} {}
  Vec3 corner(int i) const { return Vec3(coordinate[0][i], coordinate[1][i], coordinate[2][i]); }
};

// A prepared ray's values (stage 2's WatertightRay) that the lanes read in all four lanes, made
// once per ray: the origin's coordinates along the permuted axes, and the shear.
struct LanesRay {
  Float4 origin_x, origin_y, origin_z;
  Float4 shear_x, shear_y;
  float shear_z;
  explicit LanesRay(const WatertightRay& ray)
      : origin_x(broadcast(component(ray.origin, ray.kx))),
        origin_y(broadcast(component(ray.origin, ray.ky))),
        origin_z(broadcast(component(ray.origin, ray.kz))),
        shear_x(broadcast(ray.shear_x)), shear_y(broadcast(ray.shear_y)), shear_z(ray.shear_z) {}
};

// Task stage2.triangle.lanes. The contract of intersect_triangle_watertight, answered for the
// same prepared ray (`ray`, its axes, and `lanes` made from it) bit for bit as it answers. Lane i of each
// register holds corner i (a, b, c of the scalar test); lane 3 is unused.
//   1. Rows kx, ky, kz (load4), each minus the origin's coordinate; x' = x - shear_x z, y' = y - shear_y z.
//   2. The edge functions u, v, w in lanes 0, 1, 2: lane i takes the 2D cross product of the two
//      other corners, picked by rotating the lanes (__builtin_shufflevector).
//   3. Any lane exactly 0: all three again in double, as the scalar test does. Then the sign test
//      on the lanes' sign masks (lane_mask), det = (u + v) + w, t from the lanes' products
//      summed in the same order, and the bound on t (watertight_t_error_bound) from the lanes'
//      largest moduli.
std::optional<TriangleHit> intersect_triangle_lanes(const WatertightRay& ray, const LanesRay& lanes,
                                                    const TriangleCorners& triangle, Interval range);

// Defined here, not in a .cpp, for the reason the scalar test is: the BVH's leaf loop compiles it in.
[[gnu::always_inline]] inline std::optional<TriangleHit> intersect_triangle_lanes(const WatertightRay& ray,
                                                                                  const LanesRay& lanes,
                                                                                  const TriangleCorners& triangle,
                                                                                  Interval range) {
  // BEGIN TASK stage2.triangle.lanes
  const Float4 z = load4(triangle.coordinate[ray.kz]) - lanes.origin_z;
  const Float4 x = load4(triangle.coordinate[ray.kx]) - lanes.origin_x - lanes.shear_x * z;
  const Float4 y = load4(triangle.coordinate[ray.ky]) - lanes.origin_y - lanes.shear_y * z;
  // Lane 0: u = cx by - cy bx; lane 1: v = ax cy - ay cx; lane 2: w = bx ay - by ax.
  // Lane i takes its corner's two neighbours, i - 1 and i + 1 (mod 3).
  const Float4 x_prev = __builtin_shufflevector(x, x, 2, 0, 1, 3), y_prev = __builtin_shufflevector(y, y, 2, 0, 1, 3);
  const Float4 x_next = __builtin_shufflevector(x, x, 1, 2, 0, 3), y_next = __builtin_shufflevector(y, y, 1, 2, 0, 3);
  Float4 edge = x_prev * y_next - y_prev * x_next;
  if (lane_mask(edge == 0.0f) & 7u) {
    for (int i = 0; i < 3; ++i)
      edge[i] = float(double(x_prev[i]) * double(y_next[i]) - double(y_prev[i]) * double(x_next[i]));
  }
  const unsigned negative = lane_mask(edge < 0.0f) & 7u, positive = lane_mask(edge > 0.0f) & 7u;
  if ((negative != 0) & (positive != 0)) return std::nullopt;
  const float det = edge[0] + edge[1] + edge[2];
  if (det == 0.0f) return std::nullopt;

  const Float4 sheared_z = lanes.shear_z * z;
  const Float4 weighted = edge * sheared_z;
  const float inv_det = 1.0f / det;
  const float t = (weighted[0] + weighted[1] + weighted[2]) * inv_det;
  if (!range.surrounds(t)) return std::nullopt;
  const float max_z = max3(abs4(sheared_z));
  const float max_x = max3(abs4(x)), max_y = max3(abs4(y));
  const float max_edge = max3(abs4(edge));
  const float error_t = watertight_t_error_bound(max_x, max_y, max_z, max_edge, inv_det);
  if (!(t > error_t)) return std::nullopt;
  return TriangleHit{t, edge[1] * inv_det, edge[2] * inv_det};
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.lanes");
  // (void)lanes;
  // return intersect_triangle_watertight(ray, triangle.corner(0), triangle.corner(1), triangle.corner(2), range);
  // END TASK
}

}  // namespace rt
