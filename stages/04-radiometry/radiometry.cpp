#include "04-radiometry/radiometry.h"

#include "common/task.h"

namespace rt {

float area_to_solid_angle_pdf(float pdf_area, float distance, float cos_light) {
  // BEGIN TASK stage4.radiometry.area_to_solid_angle
  const float c = std::abs(cos_light);
  if (c == 0.0f) return kInfinity;
  return pdf_area * distance * distance / c;
  // PLACEHOLDER
  // report_unfinished_task("stage4.radiometry.area_to_solid_angle");
  // (void)distance, (void)cos_light;
  // return pdf_area;
  // END TASK
}

float polygon_irradiance(Vec3 p, Vec3 n, std::span<const Vec3> vertices, float radiance) {
  // BEGIN TASK stage4.radiometry.polygon_irradiance
  // Double precision: Theta_i is an angle between nearly parallel vectors for a distant polygon.
  const glm::dvec3 normal(n);
  double sum = 0.0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(vertices[i]) - glm::dvec3(p));
    const glm::dvec3 b = glm::normalize(glm::dvec3(vertices[(i + 1) % vertices.size()]) - glm::dvec3(p));
    const glm::dvec3 cross = glm::cross(a, b);
    const double sin_theta = glm::length(cross);
    if (sin_theta == 0.0) continue;
    // atan2 of sine and cosine keeps the angle accurate where acos(dot) would not be.
    sum += std::atan2(sin_theta, glm::dot(a, b)) * glm::dot(cross / sin_theta, normal);
  }
  return float(0.5 * double(radiance) * std::abs(sum));
  // PLACEHOLDER
  // report_unfinished_task("stage4.radiometry.polygon_irradiance");
  // (void)p, (void)n, (void)vertices, (void)radiance;
  // return 0.0f;
  // END TASK
}

}  // namespace rt
