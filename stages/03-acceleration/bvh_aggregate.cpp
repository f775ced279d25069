#include "03-acceleration/bvh_aggregate.h"

#include "01-ray-casting/sphere_intersection.h"

namespace rt {

FlatPrimitives::FlatPrimitives(std::shared_ptr<const PrimitiveSet> primitives) : set(std::move(primitives)) {
  const size_t spheres = set->spheres.size(), triangles = set->triangle_count();
  primitive.reserve(spheres + triangles);
  corners.reserve(spheres + triangles);
  triangle_mesh.reserve(triangles);
  triangle_index.reserve(triangles);
  for (size_t i = 0; i < spheres; ++i) {
    primitive.push_back(std::uint32_t(i));
    corners.push_back({});
  }
  for (size_t m = 0; m < set->meshes.size(); ++m) {
    const TriangleMesh& mesh = set->meshes[m].mesh;
    for (size_t k = 0; k < mesh.triangles.size(); ++k) {
      const auto& c = mesh.triangles[k];
      primitive.push_back(std::uint32_t(primitive.size()));
      corners.push_back({mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]});
      triangle_mesh.push_back(std::uint32_t(m));
      triangle_index.push_back(std::uint32_t(k));
    }
  }
}

Aabb FlatPrimitives::bounds(size_t entry) const {
  Aabb box;
  if (primitive[entry] < set->spheres.size()) {
    const Sphere& s = set->spheres[primitive[entry]].sphere;
    box.expand(s.center - Vec3(s.radius));
    box.expand(s.center + Vec3(s.radius));
  } else {
    for (const Vec3& p : corners[entry]) box.expand(p);
  }
  return box;
}

void FlatPrimitives::reorder(const std::vector<std::uint32_t>& order) {
  std::vector<std::uint32_t> new_primitive;
  std::vector<std::array<Vec3, 3>> new_corners;
  new_primitive.reserve(order.size());
  new_corners.reserve(order.size());
  for (const std::uint32_t entry : order) {
    new_primitive.push_back(primitive[entry]);
    new_corners.push_back(corners[entry]);
  }
  primitive = std::move(new_primitive);
  corners = std::move(new_corners);
}

std::optional<float> FlatPrimitives::hit(size_t i, const TriangleRay& ray, Interval range, TriangleHit* triangle_hit) const {
  if (primitive[i] < set->spheres.size()) return intersect_sphere_stable(ray.ray, set->spheres[primitive[i]].sphere, range);
  const auto& v = corners[i];
  const std::optional<TriangleHit> hit = intersect_triangle(set->triangle_method, ray, v[0], v[1], v[2], range);
  if (!hit) return std::nullopt;
  if (triangle_hit) *triangle_hit = *hit;
  return hit->t;
}

PrimitiveHit FlatPrimitives::record(size_t i, float t, const TriangleHit& triangle_hit) const {
  const size_t spheres = set->spheres.size();
  if (primitive[i] < spheres) return PrimitiveHit{t, int(primitive[i])};
  const size_t k = primitive[i] - spheres;
  return PrimitiveHit{t, -1, int(triangle_mesh[k]), int(triangle_index[k]), triangle_hit.b1, triangle_hit.b2};
}

std::optional<PrimitiveHit> NaiveAggregate::closest_hit(const Ray& ray, Interval range) const {
  std::optional<PrimitiveHit> closest;
  TriangleHit barycentrics{};
  const TriangleRay prepared(ray);
  for (size_t i = 0; i < flat_.size(); ++i)
    if (const std::optional<float> t = flat_.hit(i, prepared, range, &barycentrics)) {
      closest = flat_.record(i, *t, barycentrics);
      range.max = *t;
    }
  return closest;
}

bool NaiveAggregate::occluded(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  for (size_t i = 0; i < flat_.size(); ++i)
    if (flat_.hit(i, prepared, range)) return true;
  return false;
}

BvhAggregate::BvhAggregate(std::shared_ptr<const PrimitiveSet> primitives, const BvhBuildOptions& options)
    : flat_(std::move(primitives)) {
  std::vector<Aabb> bounds;
  bounds.reserve(flat_.size());
  for (size_t i = 0; i < flat_.size(); ++i) bounds.push_back(flat_.bounds(i));
  bvh_ = build_bvh(bounds, options);
  flat_.reorder(bvh_.order);  // entry = leaf slot from here on
  if (options.wide) wide_ = collapse_to_wide(bvh_);
}

std::optional<PrimitiveHit> BvhAggregate::closest_hit(const Ray& ray, Interval range) const {
  TriangleHit barycentrics{}, nearest_barycentrics{};
  const TriangleRay prepared(ray);
  auto hit_primitive = [&](std::uint32_t i, Interval r) {
    const std::optional<float> t = flat_.hit(i, prepared, r, &barycentrics);
    if (t) nearest_barycentrics = barycentrics;
    return t;
  };
  const auto found = wide_ ? wide_bvh_closest_hit(*wide_, ray, range, hit_primitive)
                           : bvh_closest_hit(bvh_, ray, range, hit_primitive);
  if (!found) return std::nullopt;
  return flat_.record(found->second, found->first, nearest_barycentrics);
}

bool BvhAggregate::occluded(const Ray& ray, Interval range) const {
  const TriangleRay prepared(ray);
  auto hits_primitive = [&](std::uint32_t i, Interval r) { return flat_.hit(i, prepared, r).has_value(); };
  return wide_ ? wide_bvh_any_hit(*wide_, ray, range, hits_primitive) : bvh_any_hit(bvh_, ray, range, hits_primitive);
}

size_t BvhAggregate::bytes() const {
  return bvh_.nodes.size() * sizeof(BvhNode) + (wide_ ? wide_->nodes.size() * sizeof(WideBvhNode) : 0) +
         bvh_.order.size() * sizeof(std::uint32_t) +
         flat_.size() * (sizeof(flat_.corners[0]) + sizeof(flat_.primitive[0])) +
         flat_.triangle_mesh.size() * 2 * sizeof(std::uint32_t);
}

AggregateFactory naive_aggregate_factory() {
  return [](std::shared_ptr<const PrimitiveSet> p) { return std::make_unique<NaiveAggregate>(std::move(p)); };
}

AggregateFactory bvh_aggregate_factory(const BvhBuildOptions& options) {
  return [options](std::shared_ptr<const PrimitiveSet> p) { return std::make_unique<BvhAggregate>(std::move(p), options); };
}

}  // namespace rt
