// Stage 4: the scene as stage 4 renders it: stage 2's geometry (in stage 3's BVH by default) plus
// disks, and the lights: point lights and the area emitters, with a distribution that picks an
// emitter in proportion to its power. A quad or mesh emitter is split into its triangles, each an
// emitter of its own, so a quad's two halves are chosen in proportion to their areas.
#pragma once

#include "02-whitted/whitted_scene.h"
#include "04-radiometry/discrete_distribution.h"
#include "04-radiometry/emitters.h"

namespace rt {

struct LightingOptions {
  SphereSampling sphere_sampling = SphereSampling::cone;
  TriangleMethod triangle_method = TriangleMethod::watertight;
};

class LightingScene {
 public:
  // Throws InputError naming the scene file and the shape or material for what stage 4 cannot
  // render: an emitting plane (infinite power), and a diffuse material with stage 1's empirical
  // specular highlight (use type phong). `make_aggregate` defaults to a SAH BVH (stage 3), collapsed
  // into a 4-wide tree for traversal.
  explicit LightingScene(const SceneDescription& description, const LightingOptions& options = {},
                         const AggregateFactory& make_aggregate = {});

  // As WhittedScene's, with disks too; hit.primitive is the shape's index in the scene file.
  std::optional<Hit> closest_hit(const Ray& ray, Interval range) const;
  bool occluded(const Ray& ray, Interval range) const;

  const Material& material(const Hit& hit) const { return geometry_.materials()[size_t(hit.material)]; }
  // Le leaving the hit point back along the ray: the material's emission on the front face only.
  Color emitted(const Hit& hit) const { return hit.front_face ? material(hit).emission : Color(0.0f); }
  Color background() const { return geometry_.background(); }

  const std::vector<PointLight>& point_lights() const { return geometry_.lights(); }
  const std::vector<AreaEmitter>& emitters() const { return emitters_; }
  const DiscreteDistribution& emitter_distribution() const { return emitter_distribution_; }
  // The emitter a hit landed on, or -1: the triangle's own emitter for quads and meshes.
  int emitter_index(const Hit& hit) const;
  const WhittedScene& geometry() const { return geometry_; }

 private:
  struct DiskEntry {
    Disk disk;
    int material, shape;
  };

  std::vector<int> geometry_shape_; // geometry_'s shape index -> the scene file's (filled first)
  WhittedScene geometry_;           // everything but the disks
  std::vector<DiskEntry> disks_;
  std::vector<AreaEmitter> emitters_;
  std::vector<int> first_emitter_;  // per scene-file shape: its first emitter, or -1
  DiscreteDistribution emitter_distribution_;
};

}  // namespace rt
