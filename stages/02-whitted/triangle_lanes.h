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

}  // namespace rt
