// Stage 4: the scene as stages 4 and 5 render it: stage 2's spheres and triangles plus disks, all in
// one BVH (stage 3's, by default), and the lights: point lights and the area emitters, with a
// distribution that picks an emitter in proportion to its power. A rectangular quad emitter is
// one rectangle emitter (sampled by area or by solid angle); any other quad or mesh emitter is split
// into its triangles, each an emitter of its own, so a quad's two halves are chosen in proportion
// to their areas. An environment light joins the same choice, weighted by its power through the
// scene's bounding sphere.
#pragma once

#include "02-whitted/sphere_kind.h"
#include "02-whitted/surface_scene.h"
#include "02-whitted/triangle_kind.h"
#include "04-radiometry/discrete_distribution.h"
#include "04-radiometry/disk_kind.h"
#include "04-radiometry/emitters.h"
#include "04-radiometry/environment_light.h"
#include "common/emission.h"

namespace rt {

// The registration point of stages 4 to 6: the kinds of bounded primitive they render, in the
// order every aggregate lists them.
using LightingPrimitives = PrimitiveSet<SphereKind, TriangleKind, DiskKind>;

struct LightingOptions {
  SphereSampling sphere_sampling = SphereSampling::cone;
  // Area by default: on the Cornell box solid angle lowers the error per sample by only 1.5 % and
  // costs 22 % more time per sample (docs/stage4.md, "Sampling a rectangle light").
  RectangleSampling rectangle_sampling = RectangleSampling::area;
  // Stage 2's watertight test with the corners in SIMD lanes: its answers bit for bit, faster
  // (docs/stage5.md, the speed ladder).
  TriangleMethod triangle_method = TriangleMethod::watertight_lanes;
  // By the environment map's luminance (docs/stage4.md measures the gain over uniform).
  EnvironmentSampling environment_sampling = EnvironmentSampling::importance;
};

class LightingScene : public SurfaceScene<LightingPrimitives> {
 public:
  // Throws InputError naming the scene file and the shape or material for what stage 4 cannot
  // render: a torus (stage 1's implicit surface), an emitting plane (infinite power), a diffuse
  // material with stage 1's empirical specular highlight (use type phong), and emitters whose power
  // overflows. `make_aggregate` defaults to a SAH BVH (stage 3), collapsed into a 4-wide tree for
  // traversal.
  explicit LightingScene(const SceneDescription& description, const LightingOptions& options = {},
                         const AggregateFactory<LightingPrimitives>& make_aggregate = {});

  // Le leaving the hit point back along the ray (common/emission.h).
  Color emitted(const Hit& hit) const { return front_side_emission(material(hit), hit); }

  const std::vector<AreaEmitter>& emitters() const { return emitters_; }
  // The environment light, if the scene has one (common/scene.h, Environment).
  const EnvironmentLight* environment() const { return environment_ ? &*environment_ : nullptr; }
  // What lights the scene from a direction in which nothing is hit: the environment's radiance,
  // black without one (`background` is only what the camera sees there; it lights nothing).
  Color environment_radiance(Vec3 direction) const {
    return environment_ ? environment_->radiance(direction) : Color(0.0f);
  }
  // What a ray that leaves the scene sees: the environment, or the background.
  Color escaped_radiance(Vec3 direction) const { return environment_ ? environment_->radiance(direction) : background(); }

  // Chooses what light sampling samples, by power: the area emitters are items 0 ... n - 1, and
  // the environment, if any, is item n (environment_index()).
  const DiscreteDistribution& emitter_distribution() const { return emitter_distribution_; }
  int environment_index() const { return environment_ ? int(emitters_.size()) : -1; }
  // The emitter a hit landed on, or -1: the triangle's own emitter for meshes and other quads.
  int emitter_index(const Hit& hit) const;

 private:
  std::vector<AreaEmitter> emitters_;
  std::optional<EnvironmentLight> environment_;
  struct ShapeEmitters {
    int first = -1;      // its first emitter, or -1
    bool whole = false;  // one emitter for all its triangles (a rectangle)
  };
  std::vector<ShapeEmitters> shape_emitters_;  // per scene-file shape
  DiscreteDistribution emitter_distribution_;
};

}  // namespace rt
