// Stage 1: the shapes stage 1 can render (spheres, planes, implicit tori) and the two queries every
// renderer is built on: the closest hit, and whether anything blocks a segment.
#pragma once

#include "01-ray-casting/implicit_surface.h"
#include "common/hit.h"
#include "common/interval.h"
#include "common/scene.h"

#include <optional>
#include <vector>

namespace rt {

class RayCastingScene {
 public:
  // Throws InputError naming the scene file and the shape or material when the scene holds
  // something stage 1 cannot render (triangles, quads, meshes, mirrors and glass arrive in stage 2).
  explicit RayCastingScene(const SceneDescription& description);

  // Task stage1.scene.closest_hit: the nearest hit with t strictly inside `range`, or nothing.
  // Test every shape, and shrink range.max to each hit found, so that later shapes only count
  // when they are nearer.
  std::optional<Hit> closest_hit(const Ray& ray, Interval range) const;

  // Whether any shape is hit with t strictly inside `range` (shadow rays). Stops at the first.
  bool occluded(const Ray& ray, Interval range) const;

  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PointLight>& lights() const { return lights_; }
  Color background() const { return background_; }

 private:
  std::vector<Placed<Sphere>> spheres_;
  std::vector<Placed<Plane>> planes_;
  std::vector<Placed<TorusSurface>> tori_;
  std::vector<Material> materials_;
  std::vector<PointLight> lights_;
  Color background_;
};

}  // namespace rt
