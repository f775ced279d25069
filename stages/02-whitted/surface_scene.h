// Stage 2: a scene as the later stages render it, whatever its kinds of primitives: the bounded
// ones in an Aggregate (stage 2 tests them one by one, stage 3 passes a BVH builder), the unbounded
// planes beside it, and the materials, point lights and background. A stage names its kinds once
// (WhittedPrimitives in 02-whitted/whitted_scene.h, LightingPrimitives in
// 04-radiometry/lighting_scene.h) and derives its scene from SurfaceScene<its kinds>.
#pragma once

#include "01-ray-casting/plane_intersection.h"
#include "02-whitted/aggregate.h"
#include "02-whitted/ray_offset.h"
#include "02-whitted/triangle_kind.h"
#include "common/error.h"
#include "common/frame.h"

#include <string>

namespace rt {

template <class Set>
class SurfaceScene {
 public:
  // Throws InputError naming the scene file and the shape for a shape of no kind in Set (`kinds`
  // says which shapes the stage renders, e.g. "stage 2 renders spheres, planes, ...").
  SurfaceScene(const SceneDescription& description, TriangleMethod triangle_method,
               const AggregateFactory<Set>& make_aggregate, const std::string& kinds);

  // The nearest hit with t strictly inside `range`. Its record is made once, for the nearest hit:
  // the point on the surface (barycentrics for triangles, projection for spheres, planes and disks)
  // with its error bound.
  std::optional<Hit> closest_hit(const Ray& ray, Interval range) const;
  // Whether anything is hit with t strictly inside `range`; stops at the first.
  bool occluded(const Ray& ray, Interval range) const;

  const std::vector<Material>& materials() const { return materials_; }
  const Material& material(const Hit& hit) const { return materials_[size_t(hit.material)]; }
  const std::vector<PointLight>& lights() const { return lights_; }
  Color background() const { return background_; }
  const Set& primitives() const { return *primitives_; }
  const Aggregate& aggregate() const { return *aggregate_; }
  size_t triangle_count() const { return TriangleKind::size(primitives_->template store_of<TriangleKind>()); }

 private:
  std::shared_ptr<Set> primitives_;
  std::unique_ptr<Aggregate> aggregate_;
  std::vector<Placed<Plane>> planes_;  // unbounded: tested outside the aggregate
  std::vector<Material> materials_;
  std::vector<PointLight> lights_;
  Color background_;
};

template <class Set>
SurfaceScene<Set>::SurfaceScene(const SceneDescription& description, TriangleMethod triangle_method,
                                const AggregateFactory<Set>& make_aggregate, const std::string& kinds)
    : primitives_(std::make_shared<Set>()),
      materials_(description.materials),
      lights_(description.lights),
      background_(description.background) {
  primitives_->template store_of<TriangleKind>().method = triangle_method;
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    if (const auto* plane = std::get_if<Plane>(&shape.geometry))
      planes_.push_back({*plane, shape.material, int(i)});
    else if (!primitives_->add(shape, int(i)))
      throw InputError(description.source + ": /shapes/" + std::to_string(i) + ": " + kinds);
  }
  aggregate_ = make_aggregate(primitives_);
}

template <class Set>
std::optional<Hit> SurfaceScene<Set>::closest_hit(const Ray& ray, Interval range) const {
  const std::optional<PrimitiveHit> found = aggregate_->closest_hit(ray, range);
  if (found) range.max = found->t;
  const Placed<Plane>* plane = nullptr;
  float plane_t = 0.0f;
  for (const Placed<Plane>& p : planes_)
    if (const std::optional<float> t = intersect_plane(ray, p.geometry, range)) {
      plane = &p;
      plane_t = range.max = *t;
    }
  if (plane) {
    const SurfacePoint surface = plane_point(ray.at(plane_t), plane->geometry);
    Hit hit = make_hit(ray, plane_t, surface.point, surface.error, plane->geometry.normal, plane->material, plane->shape);
    // Texture coordinates in scene units along the axes of the normal's frame: a repeating
    // texture tiles the plane with squares of side 1.
    const Frame frame = Frame::from_normal(plane->geometry.normal);
    const Vec3 d = surface.point - plane->geometry.point;
    hit.uv = Vec2(glm::dot(d, frame.s), glm::dot(d, frame.t));
    return hit;
  }
  if (!found) return std::nullopt;
  // The record is built straight into the optional that is returned. Built apart and then copied
  // in, it was read back with wider loads than the record's own stores, which the CPU cannot
  // forward: a stall at every hit (docs/stage5.md, the speed ladder, step 18).
  struct BuiltInPlace {
    const SurfaceScene& scene;
    const PrimitiveHit& found;
    const Ray& ray;
    operator Hit() const { return scene.primitives_->hit_record(found, ray); }
  };
  return std::optional<Hit>(std::in_place, BuiltInPlace{*this, *found, ray});
}

template <class Set>
bool SurfaceScene<Set>::occluded(const Ray& ray, Interval range) const {
  for (const Placed<Plane>& p : planes_)
    if (intersect_plane(ray, p.geometry, range)) return true;
  return aggregate_->occluded(ray, range);
}

}  // namespace rt
