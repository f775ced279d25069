// Stage 2: the bounded primitives of a scene (spheres and the triangles of every mesh) and the
// interface of whatever finds a ray's hits among them. Stage 2 tests them one by one
// (LinearAggregate); stage 3 builds bounding volume hierarchies behind the same interface, and the
// scene and the Whitted integrator do not change.
#pragma once

#include "02-whitted/triangle_intersection.h"
#include "common/interval.h"
#include "common/scene.h"
#include "common/triangle_mesh.h"

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace rt {

struct SphereEntry {
  Sphere sphere;
  int material, shape;  // shape: index in the scene file's shape list
};

struct MeshEntry {
  TriangleMesh mesh;  // in world space
  int material, shape;
};

struct PrimitiveSet {
  std::vector<SphereEntry> spheres;
  std::vector<MeshEntry> meshes;
  TriangleMethod triangle_method = TriangleMethod::watertight;

  size_t triangle_count() const;
};

// Which primitive a ray hit first, and where on it.
struct PrimitiveHit {
  float t;
  int sphere = -1;              // index into PrimitiveSet::spheres, or -1 for a triangle
  int mesh = -1, triangle = -1; // the triangle, when sphere == -1
  float b1 = 0.0f, b2 = 0.0f;   // its barycentrics
};

class Aggregate {
 public:
  virtual ~Aggregate() = default;
  // The nearest primitive hit with t strictly inside `range`.
  virtual std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const = 0;
  // Whether any primitive is hit with t strictly inside `range`; may stop at the first.
  virtual bool occluded(const Ray& ray, Interval range) const = 0;
};

// Builds an aggregate over a primitive set; the aggregate may keep the shared pointer.
using AggregateFactory = std::function<std::unique_ptr<Aggregate>(std::shared_ptr<const PrimitiveSet>)>;

// Stage 2's aggregate: every sphere, and every triangle of each mesh whose bounding sphere the ray
// meets (meshes of fewer than 8 triangles are tested without one: the sphere would cost as much as
// the triangles it saves).
class LinearAggregate : public Aggregate {
 public:
  explicit LinearAggregate(std::shared_ptr<const PrimitiveSet> primitives);
  std::optional<PrimitiveHit> closest_hit(const Ray& ray, Interval range) const override;
  bool occluded(const Ray& ray, Interval range) const override;

 private:
  bool misses_bound(size_t mesh, const Ray& ray, Interval range) const;
  // Both queries in one loop: the nearest hit, or with `any_hit` the first one found.
  std::optional<PrimitiveHit> search(const Ray& ray, Interval range, bool any_hit) const;

  std::shared_ptr<const PrimitiveSet> primitives_;
  std::vector<std::optional<Sphere>> bounds_;  // per mesh
};

std::unique_ptr<Aggregate> make_linear_aggregate(std::shared_ptr<const PrimitiveSet> primitives);

}  // namespace rt
