#include "02-whitted/triangle_intersection.h"

#include "02-whitted/triangle_ray.h"
#include "common/task.h"

namespace rt {

std::optional<TriangleHit> intersect_triangle(TriangleMethod method, const TriangleRay& ray, Vec3 v0, Vec3 v1,
                                              Vec3 v2, Interval range) {
  switch (method) {
    case TriangleMethod::moller_trumbore: return intersect_triangle_moller_trumbore(ray.ray, v0, v1, v2, range);
    case TriangleMethod::watertight: return intersect_triangle_watertight(ray.watertight, v0, v1, v2, range);
    case TriangleMethod::watertight_lanes:
      return intersect_triangle_lanes(ray.watertight, ray.lanes, TriangleCorners(v0, v1, v2), range);
  }
  return std::nullopt;
}

std::optional<TriangleHit> intersect_triangle_moller_trumbore(const Ray& ray, Vec3 v0, Vec3 v1, Vec3 v2,
                                                              Interval range) {
  // BEGIN TASK stage2.triangle.moller_trumbore
  const Vec3 e1 = v1 - v0, e2 = v2 - v0;
  const Vec3 s = ray.origin - v0;
  const Vec3 s1 = glm::cross(ray.direction, e2);
  const Vec3 s2 = glm::cross(s, e1);
  const float det = glm::dot(s1, e1);
  // No absolute epsilon on det: det scales with the triangle's size, so any fixed threshold drops
  // every small triangle or none. det = 0 (parallel ray, or zero area) is the only refusal; a
  // tiny det gives large or NaN b1, b2, which the comparisons below reject (NaN fails all of them).
  if (det == 0.0f) return std::nullopt;
  const float inv_det = 1.0f / det;
  const float b1 = glm::dot(s1, s) * inv_det;
  if (!(b1 >= 0.0f && b1 <= 1.0f)) return std::nullopt;
  const float b2 = glm::dot(s2, ray.direction) * inv_det;
  if (!(b2 >= 0.0f && b1 + b2 <= 1.0f)) return std::nullopt;
  const float t = glm::dot(s2, e2) * inv_det;
  if (!range.surrounds(t)) return std::nullopt;
  return TriangleHit{t, b1, b2};
  // PLACEHOLDER
  // report_unfinished_task("stage2.triangle.moller_trumbore");
  // (void)ray, (void)v0, (void)v1, (void)v2, (void)range;
  // return std::nullopt;
  // END TASK
}

WatertightRay::WatertightRay(const Ray& ray) : origin(ray.origin), direction(ray.direction) {
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

std::optional<TriangleHit> intersect_triangle_watertight(const WatertightRay& ray, Vec3 v0, Vec3 v1, Vec3 v2,
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
