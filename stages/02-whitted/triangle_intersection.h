// Stage 2: ray-triangle intersection, the lecture's Moeller-Trumbore and a watertight variant.
//
// Both find t and the barycentric coordinates (b1, b2) of o + t d = (1 - b1 - b2) v0 + b1 v1 + b2 v2,
// return the hit only when t is strictly inside `range` and the point is inside the triangle
// (edges and vertices included), and treat both faces alike (a back face is hit too). A triangle
// of zero area is never hit, and no NaN ever comes out.
#pragma once

#include "02-whitted/ray_offset.h"
#include "common/float4.h"
#include "common/interval.h"
#include "common/ray.h"

#include <optional>
#include <utility>

namespace rt {

struct TriangleHit {
  float t;
  float b1, b2;  // weights of v1 and v2; v0's is 1 - b1 - b2
};

// Task stage2.triangle.moller_trumbore. Moeller & Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 2(1), 1997. With E1 = v1 - v0, E2 = v2 - v0, S = o - v0, S1 = d x E2 and
// S2 = S x E1, Cramer's rule on [-d E1 E2] (t b1 b2)^T = S gives
//     (t, b1, b2) = (S2.E2, S1.S, S2.d) / (S1.E1).
// Fast, but b1 and b2 are rounded separately in each triangle, so a ray through an edge shared by
// two triangles can be rejected by both: a crack (docs/stage2.md measures how often).
std::optional<TriangleHit> intersect_triangle_moller_trumbore(const Ray& ray, Vec3 v0, Vec3 v1, Vec3 v2,
                                                              Interval range);

// The bound on the rounding error of the watertight test's t (Pharr, Jakob & Humphreys, Physically
// Based Rendering, 4th ed., section 6.8.4): from bounds on the sheared coordinates (the largest
// moduli max_x, max_y, max_z of the three corners' x', y', z'), then on the edge functions (the
// largest modulus max_edge), then on t = (U z'_a + V z'_b + W z'_c) / det. A hit with t not above it
// may be rounding noise: a ray that starts on the triangle. F is float, or Float4 for four
// triangles at once (triangle_pack.h), lane by lane the same arithmetic.
inline float magnitude(float x) { return std::abs(x); }
inline Float4 magnitude(Float4 x) { return abs4(x); }
template <class F>
inline F watertight_t_error_bound(F max_x, F max_y, F max_z, F max_edge, F inv_det) {
  const F error_z = gamma_bound(3) * max_z;
  const F error_x = gamma_bound(5) * (max_x + max_z);
  const F error_y = gamma_bound(5) * (max_y + max_z);
  const F error_edge = 2.0f * (gamma_bound(2) * max_x * max_y + error_y * max_x + error_x * max_y);
  return 3.0f * (gamma_bound(3) * max_edge * max_z + error_edge * max_z + error_z * max_edge) * magnitude(inv_det);
}

// Task stage2.triangle.watertight. Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection",
// JCGT 2(1), 2013. Move the origin to 0, permute the axes so that the ray's largest component is
// z, and shear so that the ray becomes the +z axis. The inside test is then three 2D edge
// functions U, V, W of the sheared vertices. Two triangles sharing an edge compute the same edge
// function from the same numbers (with opposite sign), so no ray slips between them; where one is
// exactly 0 it is recomputed in double. Needs -ffp-contract=off: a fused multiply-add breaks the
// antisymmetry (docs/build.md).
//
// The permutation and the shear depend on the ray alone, so they are computed once per ray
// (WatertightRay, task stage2.triangle.shear) and reused for every triangle the ray is tested
// against, as the paper recommends.
struct WatertightRay {
  Vec3 origin, direction;
  int kx, ky, kz;                   // the permuted axes; kz is where |d| is largest
  float shear_x, shear_y, shear_z;  // x' = x - shear_x z, y' = y - shear_y z, z' = shear_z z
  explicit WatertightRay(const Ray& ray);
};

std::optional<TriangleHit> intersect_triangle_watertight(const WatertightRay& ray, Vec3 v0, Vec3 v1, Vec3 v2,
                                                         Interval range);
inline std::optional<TriangleHit> intersect_triangle_watertight(const Ray& ray, Vec3 v0, Vec3 v1, Vec3 v2,
                                                                Interval range) {
  return intersect_triangle_watertight(WatertightRay(ray), v0, v1, v2, range);
}

}  // namespace rt
