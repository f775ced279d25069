#include "01-ray-casting/implicit_surface.h"

#include "01-ray-casting/sphere_intersection.h"
#include "common/frame.h"
#include "common/task.h"

#include <cmath>

namespace rt {

float TorusSurface::distance(Vec3 p) const {
  const Vec3 local = p - torus_.center;
  const float h = glm::dot(local, torus_.axis);
  const float rho = glm::length(local - h * torus_.axis);
  return std::hypot(rho - torus_.major_radius, h) - torus_.minor_radius;
}

Vec3 TorusSurface::gradient(Vec3 p) const {
  const Vec3 local = p - torus_.center;
  const float h = glm::dot(local, torus_.axis);
  const Vec3 radial = local - h * torus_.axis;
  const float rho = glm::length(radial);
  // On the axis every direction away from it is equally "radial"; any choice is a valid
  // subgradient there.
  const Vec3 radial_dir = rho > 0.0f ? radial / rho : Frame::from_normal(torus_.axis).s;
  // f = |q| - r with q = (rho - R, h), so grad f = q / |q| written back in 3-D.
  const Vec3 q = (rho - torus_.major_radius) * radial_dir + h * torus_.axis;
  const float length = glm::length(q);
  return length > 0.0f ? q / length : torus_.axis;  // on the core circle: any direction is a subgradient
}

std::optional<ImplicitHit> intersect_implicit(const ImplicitSurface& surface, const Ray& ray,
                                              Interval range) {
  // BEGIN TASK stage1.implicit.intersect
  const Sphere bound = surface.bounding_sphere();
  const std::optional<Interval> span = sphere_span(ray, bound);
  if (!span) return std::nullopt;
  float t = std::max(range.min, span->min);
  const float t_end = std::min(range.max, span->max);
  if (!(t < t_end)) return std::nullopt;

  // Tolerance in world units, relative to the surface's size: small against a shadow ray's
  // offset (1e-4 scene units, see shading.cpp), large against float rounding at that size.
  const float tolerance = 1e-5f * bound.radius;
  auto g = [&](float s) { return surface.distance(ray.at(s)); };
  // Newton's method on g, keeping only steps that stay in [lo, hi] and shrink |g|: near a
  // grazing hit g' -> 0 and a raw Newton step would shoot off along the ray.
  auto polish = [&](float s, float lo, float hi) {
    float value = g(s);
    for (int i = 0; i < 4 && value != 0.0f; ++i) {
      const float slope = glm::dot(surface.gradient(ray.at(s)), ray.direction);
      if (slope == 0.0f) break;
      const float next = s - value / slope;
      if (!(next >= lo && next <= hi)) break;
      const float next_value = g(next);
      if (!(std::abs(next_value) < std::abs(value))) break;
      s = next;
      value = next_value;
    }
    return s;
  };

  float previous_t = t;
  float previous_g = g(t);
  for (int step = 0; step < kMaxSphereTracingSteps; ++step) {
    const float value = g(t);
    if (std::abs(value) < tolerance) {
      const float s = polish(t, previous_t, t_end);
      if (!range.surrounds(s)) return std::nullopt;
      return ImplicitHit{s, step};
    }
    if ((value < 0.0f) != (previous_g < 0.0f)) {  // crossed the surface: bisect [previous_t, t]
      float lo = previous_t, hi = t;
      for (int i = 0; i < 40 && hi - lo > tolerance; ++i) {
        const float mid = 0.5f * (lo + hi);
        ((g(mid) < 0.0f) == (previous_g < 0.0f) ? lo : hi) = mid;
      }
      const float s = polish(0.5f * (lo + hi), lo, hi);
      if (!range.surrounds(s)) return std::nullopt;
      return ImplicitHit{s, step};
    }
    previous_t = t;
    previous_g = value;
    t += std::max(std::abs(value), 0.5f * tolerance);
    if (t > t_end) return std::nullopt;
  }
  return std::nullopt;
  // PLACEHOLDER
  // report_unfinished_task("stage1.implicit.intersect");
  // (void)surface, (void)ray, (void)range;
  // return std::nullopt;
  // END TASK
}

}  // namespace rt
