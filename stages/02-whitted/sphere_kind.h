// Stage 2: spheres as a primitive kind (the contract: 02-whitted/primitives.h). The test is stage
// 1's numerically stable one; the hit point is projected back onto the sphere with its error bound
// (02-whitted/ray_offset.h), so that secondary rays leave from the right side. Its texture
// coordinates are the latitude-longitude map's (common/spherical.h).
#pragma once

#include "01-ray-casting/sphere_intersection.h"
#include "02-whitted/primitives.h"
#include "02-whitted/ray_offset.h"
#include "common/spherical.h"

namespace rt {

struct SphereKind : PlacedGeometryKind<Sphere> {
  static Aabb bounds(const Sphere& sphere) {
    Aabb box;
    box.expand(sphere.center - Vec3(sphere.radius));
    box.expand(sphere.center + Vec3(sphere.radius));
    return box;
  }
  static std::optional<PrimitiveHit> intersect(const Store&, const Sphere& sphere, const TriangleRay& ray,
                                               Interval range) {
    const std::optional<float> t = intersect_sphere_stable(ray.ray, sphere, range);
    if (!t) return std::nullopt;
    return PrimitiveHit{*t};
  }
  static Hit hit_record(const Store& store, const PrimitiveHit& found, const Ray& ray) {
    const Placed<Sphere>& placed = store[found.index];
    const SurfacePoint surface = sphere_point(ray.at(found.t), placed.geometry);
    const Vec3 outward = sphere_normal(placed.geometry, surface.point);
    Hit hit = make_hit(ray, found.t, surface.point, surface.error, outward, placed.material, placed.shape);
    hit.uv = latlong_uv(outward);  // the sphere's (theta, phi), common/spherical.h
    return hit;
  }
};

}  // namespace rt
