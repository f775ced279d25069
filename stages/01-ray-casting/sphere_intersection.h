// Stage 1: ray-sphere intersection, the lecture's quadratic and a numerically stable form.
//
// Put the ray o + t d into |p - c|^2 = r^2. With f = o - c:
//     (d.d) t^2 + 2 (f.d) t + (f.f - r^2) = 0.
// Both functions return the NEAREST root strictly inside `range`, or nothing.
#pragma once

#include "common/interval.h"
#include "common/ray.h"
#include "common/scene.h"

#include <optional>

namespace rt {

// Task stage1.sphere.textbook. The lecture's formula: a = d.d, b = 2 f.d, c = f.f - r^2,
// t = (-b -+ sqrt(b^2 - 4ac)) / 2a.
// Kept for comparison, NOT used by the renderer: for a small sphere far away (|f| >> r) the
// discriminant b^2 - 4ac subtracts two numbers of size ~4|f|^2 whose difference ~4(r^2 - rho^2)
// is far smaller, and in float the result is rounding noise (wrong hit/miss answers from
// about |f|/r = 1e3; docs/stage1.md has the chart).
std::optional<float> intersect_sphere_textbook(const Ray& ray, const Sphere& sphere, Interval range);

// Task stage1.sphere.stable. Haines, Guenther & Akenine-Moeller, "Precision Improvements for
// Ray/Sphere Intersection", Ray Tracing Gems ch. 7 (2019):
//  1. the discriminant from the perpendicular from the centre to the line,
//     b'^2 - ac = a (r^2 - |f - (b'/a) d|^2) with b' = f.d, where no two large terms meet;
//  2. the roots without cancelling -b' against the square root: q = -(b' + sign(b') sqrt(disc)),
//     t = q / a and t = c / q (Vieta: their product is c / a).
// c itself is formed as (|f| - r)(|f| + r), which stays accurate when the origin is near the surface.
std::optional<float> intersect_sphere_stable(const Ray& ray, const Sphere& sphere, Interval range);

// Both roots of the stable form, sorted (t0 <= t1), or nothing when the line misses the sphere:
// the formula is intersect_sphere_stable's, above, which takes the nearest root in range from here.
// Used where a whole [enter, exit] span is needed (bounding spheres of implicit surfaces).
std::optional<Interval> sphere_span(const Ray& ray, const Sphere& sphere);

// Outward unit normal at a point on the sphere.
inline Vec3 sphere_normal(const Sphere& sphere, Vec3 point) {
  return (point - sphere.center) / sphere.radius;
}

}  // namespace rt
