// Stage 4: flat disks as a primitive kind (the contract: 02-whitted/primitives.h), so that a disk
// emitter lies in the same BVH as everything else. A disk is its plane, cut at the radius.
#pragma once

#include "01-ray-casting/plane_intersection.h"
#include "02-whitted/primitives.h"
#include "02-whitted/ray_offset.h"

#include <glm/exponential.hpp>

namespace rt {

struct DiskKind : PlacedGeometryKind<Disk> {
  // Along axis i a disk of radius r with unit normal n reaches r sqrt(1 - n_i^2) from its centre.
  // Near n_i = +-1 that square root magnifies the rounding of n_i^2 (to about 3e-4 r), hence the
  // pad of 1e-3 r: a box too small by a hair would let the BVH drop a hit at the rim.
  static Aabb bounds(const Disk& disk) {
    const Vec3 reach = disk.radius * (glm::sqrt(glm::max(Vec3(0.0f), 1.0f - disk.normal * disk.normal)) + 1e-3f);
    Aabb box;
    box.expand(disk.center - reach);
    box.expand(disk.center + reach);
    return box;
  }
  // Stage 1's ray-plane test (stage1.plane.intersect), then |p - c|^2 <= r^2.
  static std::optional<PrimitiveHit> intersect(const Store&, const Disk& disk, const TriangleRay& ray,
                                               Interval range) {
    const std::optional<float> t = intersect_plane(ray.ray, Plane{disk.center, disk.normal}, range);
    if (!t) return std::nullopt;
    const Vec3 d = ray.ray.at(*t) - disk.center;
    if (glm::dot(d, d) > disk.radius * disk.radius) return std::nullopt;
    return PrimitiveHit{*t};
  }
  static Hit hit_record(const Store& store, const PrimitiveHit& found, const Ray& ray) {
    const Placed<Disk>& placed = store[found.index];
    const Disk& disk = placed.geometry;
    const SurfacePoint surface = plane_point(ray.at(found.t), Plane{disk.center, disk.normal});
    return make_hit(ray, found.t, surface.point, surface.error, disk.normal, placed.material, placed.shape);
  }
};

}  // namespace rt
