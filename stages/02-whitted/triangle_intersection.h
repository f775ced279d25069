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
#include "common/task.h"

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
// against, as the paper recommends. Both are defined at the end of this header, not in a .cpp:
// the BVH's leaf loop then compiles the test into itself (no call, and the hit stays in registers
// instead of being returned through memory). Measured on the Cornell box: 2 % fewer instructions
// per path than the out-of-line test, 3 % per camera sample on the bunny (docs/stage5.md and
// docs/stage3.md, the speed ladders).
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

// Definitions of the watertight test (see above for why they are here).

inline WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), direction(ray.direction) {
  // BEGIN TASK stage2.triangle.shear
  // Permutation: z is the dimension where the direction is largest; x and y follow cyclically,
  // swapped when d_z < 0 so the triangle's winding (and the signs of U, V, W) is kept.
  // (Integer arithmetic instead of ifs: each ray has its own axes, and jumps on them are often
  // mispredicted.)
  const Vec3 abs_d = abs_components(ray.direction);
  const int x_wins = (abs_d.x > abs_d.y) & (abs_d.x > abs_d.z), y_wins = !x_wins & (abs_d.y > abs_d.z);
  kz = 2 - 2 * x_wins - y_wins;
  const int next = (kz + 1) % 3, after = (kz + 2) % 3;
  const int flip = component(ray.direction, kz) < 0.0f;
  kx = next + flip * (after - next);
  ky = after + flip * (next - after);
  // Shear that maps d onto (0, 0, 1): x' = x - (d_x/d_z) z, y' = y - (d_y/d_z) z, z' = z / d_z.
  const float d_kz = component(ray.direction, kz);
  shear_x = component(ray.direction, kx) / d_kz;
  shear_y = component(ray.direction, ky) / d_kz;
  shear_z = 1.0f / d_kz;
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.shear");
  // kx = 0, ky = 1, kz = 2;
  // shear_x = shear_y = 0.0f, shear_z = 1.0f / ray.direction.z;
  // END TASK
}

[[gnu::always_inline]] inline std::optional<TriangleHit> intersect_triangle_watertight(const WatertightRay& ray,
                                                                                        Vec3 v0, Vec3 v1, Vec3 v2,
                                                                                        Interval range) {
  // BEGIN TASK stage2.triangle.watertight
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const float shear_x = ray.shear_x, shear_y = ray.shear_y, shear_z = ray.shear_z;
  const Vec3 a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
  const float a_kz = component(a, kz), b_kz = component(b, kz), c_kz = component(c, kz);
  const float ax = component(a, kx) - shear_x * a_kz, ay = component(a, ky) - shear_y * a_kz;
  const float bx = component(b, kx) - shear_x * b_kz, by = component(b, ky) - shear_y * b_kz;
  const float cx = component(c, kx) - shear_x * c_kz, cy = component(c, ky) - shear_y * c_kz;

  // Edge functions: twice the signed area of the sheared sub-triangle opposite each vertex.
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  // On an edge the float products may cancel to exactly 0 while the true value has a sign;
  // double has room for the exact product of two floats, so the sign it gives is right.
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    u = float(double(cx) * double(by) - double(cy) * double(bx));
    v = float(double(ax) * double(cy) - double(ay) * double(cx));
    w = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  // Inside (from either side) when U, V, W do not have mixed signs; 0 counts as inside, so a ray
  // through an edge or vertex is hit by every triangle that shares it.
  // (| and & instead of || and &&: one branch for the whole test, not up to six.)
  if (((u < 0.0f) | (v < 0.0f) | (w < 0.0f)) & ((u > 0.0f) | (v > 0.0f) | (w > 0.0f))) return std::nullopt;
  const float det = u + v + w;
  if (det == 0.0f) return std::nullopt;  // zero area in projection: parallel ray or degenerate triangle

  const float az = shear_z * a_kz, bz = shear_z * b_kz, cz = shear_z * c_kz;
  const float inv_det = 1.0f / det;
  const float t = (u * az + v * bz + w * cz) * inv_det;
  if (!range.surrounds(t)) return std::nullopt;
  // A ray that starts ON the triangle (a secondary ray from an axis-aligned wall, where the offset
  // along the normal is tiny) gets a t that is rounding noise of the size of the vertex
  // coordinates. Refuse any t not above its own error bound (watertight_t_error_bound).
  const float max_z = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
  const float max_x = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
  const float max_y = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
  const float max_edge = std::max({std::abs(u), std::abs(v), std::abs(w)});
  const float error_t = watertight_t_error_bound(max_x, max_y, max_z, max_edge, inv_det);
  if (!(t > error_t)) return std::nullopt;
  return TriangleHit{t, v * inv_det, w * inv_det};
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.watertight");
  // return intersect_triangle_moller_trumbore(Ray{ray.origin, ray.direction}, v0, v1, v2, range);
  // END TASK
}

}  // namespace rt
