#include "01-ray-casting/plane_intersection.h"

#include "common/task.h"

namespace rt {

std::optional<float> intersect_plane(const Ray& ray, const Plane& plane, Interval range) {
  // BEGIN TASK stage1.plane.intersect
  const float denominator = glm::dot(ray.direction, plane.normal);
  if (denominator == 0.0f) return std::nullopt;
  const float t = glm::dot(plane.point - ray.origin, plane.normal) / denominator;
  if (!range.surrounds(t)) return std::nullopt;  // also rejects NaN and +-inf
  return t;
  // PLACEHOLDER
  // report_unfinished_task("stage1.plane.intersect");
  // (void)ray, (void)plane, (void)range;
  // return std::nullopt;
  // END TASK
}

}  // namespace rt
