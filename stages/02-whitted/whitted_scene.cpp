#include "02-whitted/whitted_scene.h"

namespace rt {
namespace {

// The materials are checked before the shapes, as they come first in a scene file.
const SceneDescription& with_whitted_materials(const SceneDescription& description) {
  for (const Material& material : description.materials)
    if (material.type == MaterialType::phong || material.type == MaterialType::microfacet)
      throw InputError(description.source + ": /materials/" + material.name +
                       ": stage 2 renders diffuse, mirror and dielectric materials (phong and "
                       "microfacet come with stage 4)");
  return description;
}

}  // namespace

WhittedScene::WhittedScene(const SceneDescription& description, TriangleMethod triangle_method,
                           const AggregateFactory<WhittedPrimitives>& make_aggregate)
    : SurfaceScene(with_whitted_materials(description), triangle_method, make_aggregate,
                   "stage 2 renders spheres, planes, triangles, quads and meshes (tori are stage 1's "
                   "implicit surfaces, disks come with stage 4)") {}

}  // namespace rt
