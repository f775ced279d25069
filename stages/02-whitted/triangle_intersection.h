// Stage 2: ray-triangle intersection, the lecture's Moeller-Trumbore and a watertight variant.
//
// Both find t and the barycentric coordinates (b1, b2) of o + t d = (1 - b1 - b2) v0 + b1 v1 + b2 v2,
// return the hit only when t is strictly inside `range` and the point is inside the triangle
// (edges and vertices included), and treat both faces alike (a back face is hit too). A triangle
// of zero area is never hit, and no NaN ever comes out.
#pragma once

#include "common/interval.h"
#include "common/ray.h"

#include <optional>

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

enum class TriangleMethod { moller_trumbore, watertight };

// A ray with what either test needs, prepared once.
struct TriangleRay {
  Ray ray;
  WatertightRay watertight;
  explicit TriangleRay(const Ray& r) : ray(r), watertight(r) {}
};

inline std::optional<TriangleHit> intersect_triangle(TriangleMethod method, const TriangleRay& ray, Vec3 v0,
                                                     Vec3 v1, Vec3 v2, Interval range) {
  return method == TriangleMethod::watertight ? intersect_triangle_watertight(ray.watertight, v0, v1, v2, range)
                                              : intersect_triangle_moller_trumbore(ray.ray, v0, v1, v2, range);
}
inline std::optional<TriangleHit> intersect_triangle(TriangleMethod method, const Ray& ray, Vec3 v0, Vec3 v1,
                                                     Vec3 v2, Interval range) {
  return intersect_triangle(method, TriangleRay(ray), v0, v1, v2, range);
}

}  // namespace rt
