// Stage 2: the scene as stage 2 renders it: spheres, planes and triangle meshes (a scene file's
// triangles, quads and OBJ meshes all become meshes), with the two queries of stage 1 (closest hit,
// occlusion) now also reporting where the hit point is to within its rounding error.
#pragma once

#include "02-whitted/triangle_intersection.h"
#include "common/hit.h"
#include "common/interval.h"
#include "common/scene.h"
#include "common/triangle_mesh.h"

#include <optional>
#include <vector>

namespace rt {

class WhittedScene {
 public:
  // Throws InputError naming the scene file and the shape for a torus (implicit surfaces are
  // stage 1's exercise; from stage 2 on, shapes are spheres, planes and triangles).
  explicit WhittedScene(const SceneDescription& description,
                        TriangleMethod triangle_method = TriangleMethod::watertight);

  // The nearest hit with t strictly inside `range`. The hit's point is computed on the surface
  // (barycentrics for triangles, projection for spheres and planes) with its error bound.
  std::optional<Hit> closest_hit(const Ray& ray, Interval range) const;
  // Whether anything is hit with t strictly inside `range`; stops at the first.
  bool occluded(const Ray& ray, Interval range) const;

  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PointLight>& lights() const { return lights_; }
  Color background() const { return background_; }
  size_t triangle_count() const;

 private:
  struct SphereEntry {
    Sphere sphere;
    int material, shape;
  };
  struct PlaneEntry {
    Plane plane;
    int material, shape;
  };
  // A mesh in world space. Rays that miss its bounding sphere skip all of its triangles (one
  // cheap test instead of many; stage 3 replaces this with a real hierarchy).
  struct MeshEntry {
    TriangleMesh mesh;
    std::optional<Sphere> bound;
    int material, shape;
  };

  // Whether the ray misses the mesh's bounding sphere within `range` (false without one).
  static bool misses_bound(const MeshEntry& entry, const Ray& ray, Interval range);
  // The nearest triangle of `entry` hit inside `range` (shrinking nothing), or nothing.
  std::optional<std::pair<TriangleHit, int>> nearest_triangle(const MeshEntry& entry, const Ray& ray,
                                                              Interval range) const;
  Hit triangle_hit_record(const MeshEntry& entry, int triangle, const TriangleHit& found,
                          const Ray& ray) const;

  std::vector<SphereEntry> spheres_;
  std::vector<PlaneEntry> planes_;
  std::vector<MeshEntry> meshes_;
  TriangleMethod triangle_method_;
  std::vector<Material> materials_;
  std::vector<PointLight> lights_;
  Color background_;
};

}  // namespace rt
