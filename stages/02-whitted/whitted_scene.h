// Stage 2: the scene as stage 2 renders it: planes, plus spheres and triangle meshes held by an
// Aggregate (a scene file's triangles, quads and OBJ meshes all become meshes). The two queries of
// stage 1 (closest hit, occlusion) now also report where the hit point is to within its rounding
// error.
#pragma once

#include "02-whitted/aggregate.h"
#include "common/hit.h"

namespace rt {

class WhittedScene {
 public:
  // Throws InputError naming the scene file and the shape for a torus (implicit surfaces are
  // stage 1's exercise; from stage 2 on, shapes are spheres, planes and triangles).
  // `make_aggregate` decides how the bounded primitives are searched: stage 2 tests them one by
  // one, stage 3 passes a BVH builder.
  explicit WhittedScene(const SceneDescription& description,
                        TriangleMethod triangle_method = TriangleMethod::watertight,
                        const AggregateFactory& make_aggregate = make_linear_aggregate);

  // The nearest hit with t strictly inside `range`. The hit's point is computed on the surface
  // (barycentrics for triangles, projection for spheres and planes) with its error bound.
  std::optional<Hit> closest_hit(const Ray& ray, Interval range) const;
  // Whether anything is hit with t strictly inside `range`; stops at the first.
  bool occluded(const Ray& ray, Interval range) const;

  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PointLight>& lights() const { return lights_; }
  Color background() const { return background_; }
  size_t triangle_count() const { return primitives_->triangle_count(); }
  const PrimitiveSet& primitives() const { return *primitives_; }
  const Aggregate& aggregate() const { return *aggregate_; }

 private:
  struct PlaneEntry {
    Plane plane;
    int material, shape;
  };

  Hit triangle_hit_record(const PrimitiveHit& found, const Ray& ray) const;
  Hit sphere_hit_record(const PrimitiveHit& found, const Ray& ray) const;

  std::shared_ptr<PrimitiveSet> primitives_;
  std::unique_ptr<Aggregate> aggregate_;
  std::vector<PlaneEntry> planes_;  // unbounded: tested outside the aggregate
  std::vector<Material> materials_;
  std::vector<PointLight> lights_;
  Color background_;
};

}  // namespace rt
