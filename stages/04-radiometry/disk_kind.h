// Stage 4: flat disks as a primitive kind (the contract: 02-whitted/primitives.h), so that a disk
// emitter lies in the same BVH as everything else. A disk is its plane, cut at the radius.
#pragma once

#include "01-ray-casting/plane_intersection.h"
#include "02-whitted/primitives.h"
#include "02-whitted/ray_offset.h"
#include "common/frame.h"

#include <glm/exponential.hpp>

#include <cmath>

namespace rt {

struct DiskKind : PlacedGeometryKind<Disk> {
  // Along axis i a disk of radius r with unit normal n reaches r sqrt(1 - n_i^2) = r sqrt(n_j^2 +
  // n_k^2) from its centre. The second form has no cancellation: for a disk tilted by 1e-4 from an
  // axis, n_i rounds to 1 and the first would give a flat box that the rim pokes out of. The pad
  // of 1e-5 covers the rounding of the reach, and |n| being 1 only to float precision; c +- reach
  // is then rounded outwards, a float step beyond.
  static Aabb bounds(const Disk& disk) {
    const Vec3 n2 = disk.normal * disk.normal;
    const Vec3 reach = disk.radius * 1.00001f * glm::sqrt(Vec3(n2.y + n2.z, n2.x + n2.z, n2.x + n2.y));
    Aabb box;
    for (int axis = 0; axis < 3; ++axis) {
      box.lo[axis] = std::nextafter(disk.center[axis] - reach[axis], -kInfinity);
      box.hi[axis] = std::nextafter(disk.center[axis] + reach[axis], kInfinity);
    }
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
    Hit hit = make_hit(ray, found.t, surface.point, surface.error, disk.normal, placed.material, placed.shape);
    // The disk inscribed in the unit square of texture space, along the axes of its normal's frame.
    const Frame frame = Frame::from_normal(disk.normal);
    const Vec3 d = surface.point - disk.center;
    hit.uv = Vec2(0.5f) + Vec2(glm::dot(d, frame.s), glm::dot(d, frame.t)) * (0.5f / disk.radius);
    return hit;
  }
};

}  // namespace rt
