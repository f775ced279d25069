// Stage 2: the scene as stages 2 and 3 render it: spheres and triangles (a scene file's triangles,
// quads and OBJ meshes) held by an Aggregate, planes beside it, and materials that are diffuse,
// mirrors or glass.
#pragma once

#include "02-whitted/sphere_kind.h"
#include "02-whitted/surface_scene.h"
#include "02-whitted/triangle_kind.h"

namespace rt {

// The registration point of stages 2 and 3: the kinds of bounded primitive they render, in the
// order every aggregate lists them.
using WhittedPrimitives = PrimitiveSet<SphereKind, TriangleKind>;

class WhittedScene : public SurfaceScene<WhittedPrimitives> {
 public:
  // Throws InputError naming the scene file and the material or shape for what stage 2 cannot
  // render: phong and microfacet materials (stage 4's energy-conserving BRDFs), tori (stage 1's
  // implicit surfaces) and disks (stage 4's emitters). `make_aggregate` decides how the bounded
  // primitives are searched: stage 2 tests them one by one, stage 3 passes a BVH builder.
  explicit WhittedScene(const SceneDescription& description,
                        TriangleMethod triangle_method = TriangleMethod::watertight,
                        const AggregateFactory<WhittedPrimitives>& make_aggregate =
                            make_linear_aggregate<WhittedPrimitives>);
};

}  // namespace rt
