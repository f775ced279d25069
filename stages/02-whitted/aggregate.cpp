#include "02-whitted/aggregate.h"

#include "01-ray-casting/sphere_intersection.h"

namespace rt {
namespace {

constexpr size_t kBoundingSphereMinTriangles = 8;

// A sphere around every vertex, padded by a relative 1e-4 so that rounding in the sphere test can
// never reject a ray that hits a triangle.
Sphere bounding_sphere(const TriangleMesh& mesh) {
  Vec3 lo(kInfinity), hi(-kInfinity);
  for (const Vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec3 center = 0.5f * (lo + hi);
  float radius = 0.0f;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, glm::length(p - center));
  return Sphere{center, radius * (1.0f + 1e-4f) + 1e-30f};
}

}  // namespace

size_t PrimitiveSet::triangle_count() const {
  size_t count = 0;
  for (const MeshEntry& entry : meshes) count += entry.mesh.triangles.size();
  return count;
}

LinearAggregate::LinearAggregate(std::shared_ptr<const PrimitiveSet> primitives)
    : primitives_(std::move(primitives)) {
  for (const MeshEntry& entry : primitives_->meshes)
    bounds_.push_back(entry.mesh.triangles.size() >= kBoundingSphereMinTriangles
                          ? std::optional<Sphere>(bounding_sphere(entry.mesh))
                          : std::nullopt);
}

bool LinearAggregate::misses_bound(size_t mesh, const Ray& ray, Interval range) const {
  if (!bounds_[mesh]) return false;
  const std::optional<Interval> span = sphere_span(ray, *bounds_[mesh]);
  return !span || span->max <= range.min || span->min >= range.max;
}

std::optional<PrimitiveHit> LinearAggregate::search(const Ray& ray, Interval range, bool any_hit) const {
  std::optional<PrimitiveHit> found;
  for (size_t i = 0; i < primitives_->spheres.size(); ++i)
    if (const auto t = intersect_sphere_stable(ray, primitives_->spheres[i].sphere, range)) {
      found = PrimitiveHit{*t, int(i)};
      if (any_hit) return found;
      range.max = *t;
    }
  const TriangleMethod method = primitives_->triangle_method;
  const TriangleRay prepared(ray);
  for (size_t m = 0; m < primitives_->meshes.size(); ++m) {
    if (misses_bound(m, ray, range)) continue;
    const TriangleMesh& mesh = primitives_->meshes[m].mesh;
    const auto& p = mesh.positions;
    for (size_t k = 0; k < mesh.triangles.size(); ++k) {
      const auto& c = mesh.triangles[k];
      if (const auto hit = intersect_triangle(method, prepared, p[c[0]], p[c[1]], p[c[2]], range)) {
        found = PrimitiveHit{hit->t, -1, int(m), int(k), hit->b1, hit->b2};
        if (any_hit) return found;
        range.max = hit->t;
      }
    }
  }
  return found;
}

std::optional<PrimitiveHit> LinearAggregate::closest_hit(const Ray& ray, Interval range) const {
  return search(ray, range, false);
}

bool LinearAggregate::occluded(const Ray& ray, Interval range) const { return search(ray, range, true).has_value(); }

std::unique_ptr<Aggregate> make_linear_aggregate(std::shared_ptr<const PrimitiveSet> primitives) {
  return std::make_unique<LinearAggregate>(std::move(primitives));
}

}  // namespace rt
