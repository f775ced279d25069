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

}  // namespace rt
