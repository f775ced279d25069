#include "01-ray-casting/sphere_intersection.h"

#include "common/task.h"

#include <cmath>
#include <utility>

namespace rt {
namespace {

// The nearer of two sorted roots that lies strictly inside the range.
std::optional<float> nearest_in(float t0, float t1, Interval range) {
  if (range.surrounds(t0)) return t0;
  if (range.surrounds(t1)) return t1;
  return std::nullopt;
}

}  // namespace

std::optional<float> intersect_sphere_textbook(const Ray& ray, const Sphere& sphere, Interval range) {
  // BEGIN TASK stage1.sphere.textbook
  const Vec3 f = ray.origin - sphere.center;
  const float a = glm::dot(ray.direction, ray.direction);
  const float b = 2.0f * glm::dot(f, ray.direction);
  const float c = glm::dot(f, f) - sphere.radius * sphere.radius;
  const float discriminant = b * b - 4.0f * a * c;
  if (discriminant < 0.0f) return std::nullopt;
  const float root = std::sqrt(discriminant);
  return nearest_in((-b - root) / (2.0f * a), (-b + root) / (2.0f * a), range);
  // PLACEHOLDER
  // report_unfinished_task("stage1.sphere.textbook");
  // (void)ray, (void)sphere, (void)range;
  // return std::nullopt;
  // END TASK
}

std::optional<Interval> sphere_span(const Ray& ray, const Sphere& sphere) {
  // BEGIN TASK stage1.sphere.stable
  const Vec3 f = ray.origin - sphere.center;
  const float a = glm::dot(ray.direction, ray.direction);
  const float b_half = glm::dot(f, ray.direction);
  const Vec3 perpendicular = f - (b_half / a) * ray.direction;
  const float discriminant =
      a * (sphere.radius * sphere.radius - glm::dot(perpendicular, perpendicular));
  if (discriminant < 0.0f) return std::nullopt;
  const float distance = glm::length(f);
  const float c = (distance - sphere.radius) * (distance + sphere.radius);
  const float q = -(b_half + std::copysign(std::sqrt(discriminant), b_half));
  if (q == 0.0f) return Interval{0.0f, 0.0f};  // origin on the surface, ray tangent to it
  float t0 = c / q, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  return Interval{t0, t1};
  // PLACEHOLDER
  // report_unfinished_task("stage1.sphere.stable");
  // (void)ray, (void)sphere;
  // return std::nullopt;
  // END TASK
}

std::optional<float> intersect_sphere_stable(const Ray& ray, const Sphere& sphere, Interval range) {
  const std::optional<Interval> span = sphere_span(ray, sphere);
  if (!span) return std::nullopt;
  return nearest_in(span->min, span->max, range);
}

}  // namespace rt
