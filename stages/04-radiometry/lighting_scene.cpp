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

// A quad that is a rectangle: its opposite sides equal and its corners right angles, each to a
// relative 1e-5 (a scene file's decimals), as corner + s edge_u + t edge_v.
std::optional<RectangleEmitter> rectangle_of(const Quad& quad, RectangleSampling strategy) {
  const auto& v = quad.vertices;
  const Vec3 edge_u = v[1] - v[0], edge_v = v[3] - v[0];
  const float lu = glm::length(edge_u), lv = glm::length(edge_v);
  const float tolerance = 1e-5f * std::max(lu, lv);
  if (!(lu > 0.0f && lv > 0.0f) || glm::length(v[2] - (v[1] + edge_v)) > tolerance ||
      std::abs(glm::dot(edge_u, edge_v)) > tolerance * std::min(lu, lv))
    return std::nullopt;
  return RectangleEmitter{v[0], edge_u, edge_v, strategy};
}

// The radius of a sphere around every bounded primitive (half its box's diagonal); 1 for a scene
// of planes alone.
template <class Set>
float bounding_radius(const Set& primitives) {
  Aabb box;
  primitives.for_each_kind([&](auto k) {
    using Kind = typename Set::template Kind<k>;
    const auto& store = primitives.template store<k>();
    for (size_t i = 0; i < Kind::size(store); ++i) box.expand(Kind::bounds(Kind::hot(store, i)));
  });
  const float radius = 0.5f * glm::length(box.hi - box.lo);
  return radius > 0.0f && std::isfinite(radius) ? radius : 1.0f;
}

}  // namespace

LightingScene::LightingScene(const SceneDescription& description, const LightingOptions& options,
                             const AggregateFactory<LightingPrimitives>& make_aggregate)
    : SurfaceScene(with_lighting_materials(description), options.triangle_method,
                   make_aggregate ? make_aggregate
                                  : bvh_aggregate_factory<LightingPrimitives>(BvhBuildOptions{.wide = true}),
                   "stage 4 renders spheres, planes, triangles, quads, meshes and disks (tori are stage 1's "
                   "implicit surfaces)") {
  shape_emitters_.assign(description.shapes.size(), ShapeEmitters{});
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    const Color le = description.materials[size_t(shape.material)].emission;
    if (max_component(le) <= 0.0f) continue;
    shape_emitters_[i].first = int(emitters_.size());
    auto add = [&](auto geometry) { emitters_.push_back(AreaEmitter{geometry, le, int(i)}); };
    const auto* quad = std::get_if<Quad>(&shape.geometry);
    const std::optional<RectangleEmitter> rectangle =
        quad ? rectangle_of(*quad, options.rectangle_sampling) : std::nullopt;
    if (rectangle) {
      add(*rectangle);
      shape_emitters_[i].whole = true;
    } else if (const auto* sphere = std::get_if<Sphere>(&shape.geometry))
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
  if (description.environment) {
    environment_.emplace(*description.environment, options.environment_sampling);
    power.push_back(environment_->power(bounding_radius(primitives())));
    total += double(power.back());
    if (!std::isfinite(power.back()) || total > double(std::numeric_limits<float>::max()))
      throw InputError(description.source + ": /environment: its power through the scene's bounding sphere "
                       "(pi r^2 x integral of L) overflows float: make it dimmer or the scene smaller");
  }
  emitter_distribution_ = DiscreteDistribution(power);
}

int LightingScene::emitter_index(const Hit& hit) const {
  if (hit.primitive < 0 || size_t(hit.primitive) >= shape_emitters_.size()) return -1;
  const ShapeEmitters& e = shape_emitters_[size_t(hit.primitive)];
  if (e.first < 0) return -1;
  return e.whole ? e.first : e.first + std::max(0, hit.triangle);
}

}  // namespace rt
