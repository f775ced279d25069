#include "04-radiometry/lighting_scene.h"

#include "02-whitted/mesh_instance.h"
#include "03-acceleration/bvh_aggregate.h"
#include "common/error.h"

#include <cmath>
#include <limits>

namespace rt {

namespace {

// The materials are checked before the shapes, as they come first in a scene file.
const SceneDescription& with_lighting_materials(const SceneDescription& description) {
  for (const Material& m : description.materials)
    if (m.type == MaterialType::diffuse && max_component(m.specular) > 0.0f)
      throw InputError(description.source + ": /materials/" + m.name +
                       ": stage 4 renders diffuse materials as Lambertian; stage 1's specular "
                       "highlight is not energy conserving (use type phong)");
  return description;
}

}  // namespace

LightingScene::LightingScene(const SceneDescription& description, const LightingOptions& options,
                             const AggregateFactory<LightingPrimitives>& make_aggregate)
    : SurfaceScene(with_lighting_materials(description), options.triangle_method,
                   make_aggregate ? make_aggregate
                                  : bvh_aggregate_factory<LightingPrimitives>(BvhBuildOptions{.wide = true}),
                   "stage 4 renders spheres, planes, triangles, quads, meshes and disks (tori are stage 1's "
                   "implicit surfaces)") {
  first_emitter_.assign(description.shapes.size(), -1);
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    const Color le = description.materials[size_t(shape.material)].emission;
    if (max_component(le) <= 0.0f) continue;
    first_emitter_[i] = int(emitters_.size());
    auto add = [&](auto geometry) { emitters_.push_back(AreaEmitter{geometry, le, int(i)}); };
    if (const auto* sphere = std::get_if<Sphere>(&shape.geometry))
      add(SphereEmitter{sphere->center, sphere->radius, options.sphere_sampling});
    else if (const auto* disk = std::get_if<Disk>(&shape.geometry))
      add(DiskEmitter{disk->center, disk->normal, disk->radius});
    else if (const std::optional<TriangleMesh> mesh = triangles_of(shape.geometry))
      for (const auto& t : mesh->triangles)
        add(TriangleEmitter{mesh->positions[t[0]], mesh->positions[t[1]], mesh->positions[t[2]]});
    else
      throw InputError(description.source + ": /shapes/" + std::to_string(i) +
                       ": an emitting plane would have infinite power; use a quad or a disk");
  }
  // Emitters are chosen by power, Phi = pi Le A: an overflow to inf there would make every pdf
  // NaN and every pixel NaN. The sum is formed in double, as the distribution's total is in float.
  std::vector<float> power;
  double total = 0.0;
  for (const AreaEmitter& e : emitters_) {
    power.push_back(e.power());
    total += double(power.back());
    if (!std::isfinite(power.back()) || total > double(std::numeric_limits<float>::max()))
      throw InputError(description.source + ": /shapes/" + std::to_string(e.shape) +
                       ": the emitted power (pi x radiance x area) overflows float: make the emitters dimmer or "
                       "smaller");
  }
  emitter_distribution_ = DiscreteDistribution(power);
}

int LightingScene::emitter_index(const Hit& hit) const {
  if (hit.primitive < 0 || size_t(hit.primitive) >= first_emitter_.size()) return -1;
  const int first = first_emitter_[size_t(hit.primitive)];
  if (first < 0) return -1;
  return first + std::max(0, hit.triangle);
}

}  // namespace rt
