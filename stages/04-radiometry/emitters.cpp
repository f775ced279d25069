#include "04-radiometry/emitters.h"

#include "04-radiometry/radiometry.h"
#include "04-radiometry/spherical_rectangle.h"
#include "04-radiometry/warp.h"
#include "common/emission.h"
#include "common/frame.h"
#include "common/task.h"

namespace rt {

namespace {

// The sample towards y, with y's area density converted to solid angle at x.
EmitterSample towards(Vec3 x, Vec3 y, Vec3 normal, float pdf_area) {
  const Vec3 d = y - x;
  const float distance = glm::length(d);
  const Vec3 wi = d / distance;
  return EmitterSample{y, wi, distance, area_to_solid_angle_pdf(pdf_area, distance, glm::dot(normal, -wi))};
}

float area_pdf_as_solid_angle(Vec3 x, Vec3 y, Vec3 normal, float pdf_area) {
  const Vec3 d = y - x;
  const float distance = glm::length(d);
  return area_to_solid_angle_pdf(pdf_area, distance, glm::dot(normal, d) / distance);
}

}  // namespace

float TriangleEmitter::area() const { return 0.5f * glm::length(glm::cross(v1 - v0, v2 - v0)); }

Vec3 TriangleEmitter::normal() const { return glm::normalize(glm::cross(v1 - v0, v2 - v0)); }

EmitterSample TriangleEmitter::sample(Vec3 x, Vec2 u) const {
  // BEGIN TASK stage4.light.triangle
  const Vec3 b = sample_uniform_triangle(u);
  const Vec3 y = b.x * v0 + b.y * v1 + b.z * v2;
  return towards(x, y, normal(), 1.0f / area());
  // PLACEHOLDER
  // report_unfinished_task("stage4.light.triangle");
  // (void)u;
  // return towards(x, (v0 + v1 + v2) / 3.0f, normal(), 1.0f / area());
  // END TASK
}

float TriangleEmitter::pdf(Vec3 x, Vec3 y) const { return area_pdf_as_solid_angle(x, y, normal(), 1.0f / area()); }

// Both first ask whether x is in front: on the side of the plane that `front` points to.
EmitterSample RectangleEmitter::sample(Vec3 x, Vec2 u) const {
  if (!(glm::dot(front, x - corner) > 0.0f)) return EmitterSample{corner, Vec3(0.0f), 0.0f, 0.0f};
  if (strategy == RectangleSampling::solid_angle) {
    const SphericalRectangle seen(x, corner, edge_u, edge_v);
    if (seen.solid_angle() >= kMinSolidAngle) {
      const Vec3 y = seen.sample(u);
      const float distance = glm::length(y - x);
      return EmitterSample{y, (y - x) / distance, distance, 1.0f / seen.solid_angle()};
    }
  }
  return towards(x, corner + u.x * edge_u + u.y * edge_v, unit_normal, inverse_area);
}

float RectangleEmitter::pdf(Vec3 x, Vec3 y) const {
  if (!(glm::dot(front, x - corner) > 0.0f)) return 0.0f;
  if (strategy == RectangleSampling::solid_angle) {
    const float solid_angle = SphericalRectangle(x, corner, edge_u, edge_v).solid_angle();
    if (solid_angle >= kMinSolidAngle) return 1.0f / solid_angle;
  }
  return area_pdf_as_solid_angle(x, y, unit_normal, inverse_area);
}

EmitterSample DiskEmitter::sample(Vec3 x, Vec2 u) const {
  const Frame frame = Frame::from_normal(normal);
  const Vec2 d = radius * sample_uniform_disk(u);
  return towards(x, center + d.x * frame.s + d.y * frame.t, normal, 1.0f / area());
}

float DiskEmitter::pdf(Vec3 x, Vec3 y) const { return area_pdf_as_solid_angle(x, y, normal, 1.0f / area()); }

namespace {

struct Cone {
  float cos_theta_max;
  bool inside;  // x is inside the sphere: no cone
};

Cone subtended_cone(Vec3 x, Vec3 center, float radius) {
  const Vec3 d = center - x;
  const float dist2 = glm::dot(d, d);
  const float sin2 = radius * radius / dist2;
  if (!(sin2 < 1.0f)) return Cone{-1.0f, true};
  return Cone{std::sqrt(1.0f - sin2), false};
}

}  // namespace

EmitterSample SphereEmitter::sample(Vec3 x, Vec2 u) const {
  const Cone cone = subtended_cone(x, center, radius);
  if (strategy == SphereSampling::area || cone.inside) {
    const Vec3 n = sample_uniform_sphere(u);
    return towards(x, center + radius * n, n, 1.0f / area());
  }
  // BEGIN TASK stage4.light.sphere_cone
  const Vec3 to_center = center - x;
  const float dc = glm::length(to_center);
  const Vec3 wi = Frame::from_normal(to_center / dc).to_world(sample_uniform_cone(u, cone.cos_theta_max));
  // The nearer root of |x + t wi - c| = r: t = dc cos(theta) - sqrt(r^2 - dc^2 sin^2(theta)). The
  // radicand is >= 0 inside the cone, up to rounding at its rim (where the ray grazes the sphere).
  const float cos_theta = glm::dot(wi, to_center) / dc;
  const float sin2_theta = std::max(0.0f, 1.0f - cos_theta * cos_theta);
  const float t = dc * cos_theta - std::sqrt(std::max(0.0f, radius * radius - dc * dc * sin2_theta));
  return EmitterSample{x + t * wi, wi, t, uniform_cone_pdf(cone.cos_theta_max)};
  // PLACEHOLDER
  // report_unfinished_task("stage4.light.sphere_cone");
  // const Vec3 n = sample_uniform_sphere(u);
  // return towards(x, center + radius * n, n, 1.0f / area());
  // END TASK
}

float SphereEmitter::pdf(Vec3 x, Vec3 y) const {
  const Cone cone = subtended_cone(x, center, radius);
  if (strategy == SphereSampling::area || cone.inside) return area_pdf_as_solid_angle(x, y, normal_at(y), 1.0f / area());
  return uniform_cone_pdf(cone.cos_theta_max);
}

Vec3 AreaEmitter::normal_at(Vec3 y) const {
  if (const auto* t = std::get_if<TriangleEmitter>(&geometry)) return t->normal();
  if (const auto* r = std::get_if<RectangleEmitter>(&geometry)) return r->normal();
  if (const auto* d = std::get_if<DiskEmitter>(&geometry)) return d->normal;
  return glm::normalize(std::get<SphereEmitter>(geometry).normal_at(y));
}

Color AreaEmitter::radiance_towards(Vec3 y, Vec3 x) const {
  return front_side_emission(radiance, glm::dot(normal_at(y), x - y) > 0.0f);
}

float AreaEmitter::power() const { return luminance(lambertian_emitter_flux(radiance, area())); }

}  // namespace rt
