#include "02-whitted/aggregate.h"

namespace rt {

Sphere bounding_sphere(const std::vector<Aabb>& boxes) {
  Aabb all;
  for (const Aabb& box : boxes) all.expand(box);
  const Vec3 center = all.centroid();
  float radius = 0.0f;
  for (const Aabb& box : boxes) {
    // The corner of the box farthest from the centre, axis by axis.
    const Vec3 far = glm::max(glm::abs(box.lo - center), glm::abs(box.hi - center));
    radius = std::max(radius, glm::length(far));
  }
  return Sphere{center, radius * (1.0f + 1e-4f) + 1e-30f};
}

}  // namespace rt
