#include "02-whitted/whitted_scene.h"

#include "01-ray-casting/plane_intersection.h"
#include "01-ray-casting/sphere_intersection.h"
#include "02-whitted/mesh_instance.h"
#include "02-whitted/ray_offset.h"
#include "common/error.h"
#include "common/task.h"

namespace rt {

WhittedScene::WhittedScene(const SceneDescription& description, TriangleMethod triangle_method,
                           const AggregateFactory& make_aggregate)
    : primitives_(std::make_shared<PrimitiveSet>()),
      materials_(description.materials),
      lights_(description.lights),
      background_(description.background) {
  primitives_->triangle_method = triangle_method;
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    const int index = int(i);
    if (const auto* sphere = std::get_if<Sphere>(&shape.geometry))
      primitives_->spheres.push_back({*sphere, shape.material, index});
    else if (const auto* plane = std::get_if<Plane>(&shape.geometry))
      planes_.push_back({*plane, shape.material, index});
    else if (std::optional<TriangleMesh> mesh = triangles_of(shape.geometry))
      primitives_->meshes.push_back({std::move(*mesh), shape.material, index});
    else
      throw InputError(description.source + ": /shapes/" + std::to_string(i) +
                       ": stage 2 renders spheres, planes, triangles, quads and meshes (tori are "
                       "stage 1's implicit surfaces, disks come with stage 4)");
  }
  aggregate_ = make_aggregate(primitives_);
}

Hit WhittedScene::triangle_hit_record(const PrimitiveHit& found, const Ray& ray) const {
  const MeshEntry& entry = primitives_->meshes[size_t(found.mesh)];
  const TriangleMesh& mesh = entry.mesh;
  const int triangle = found.triangle;
  const auto& corners = mesh.triangles[size_t(triangle)];
  const Vec3 v0 = mesh.positions[corners[0]], v1 = mesh.positions[corners[1]], v2 = mesh.positions[corners[2]];
  Hit hit;
  hit.t = found.t;
  hit.material = entry.material;
  hit.primitive = entry.shape;
  hit.triangle = triangle;
  // BEGIN TASK stage2.mesh.hit_record
  const Vec3 b(1.0f - found.b1 - found.b2, found.b1, found.b2);
  const SurfacePoint surface = triangle_point(b, v0, v1, v2);
  hit.point = surface.point;
  hit.point_error = surface.error;
  hit.set_face_normal(ray, glm::normalize(glm::cross(v1 - v0, v2 - v0)));
  if (mesh.has_normals(size_t(triangle))) {
    // Phong-style normal interpolation: the barycentric blend of the vertex normals, turned to the
    // side the ray came from like the geometric normal.
    const auto& ni = mesh.triangle_normals[size_t(triangle)];
    const Vec3 blend = b.x * mesh.normals[size_t(ni[0])] + b.y * mesh.normals[size_t(ni[1])] +
                       b.z * mesh.normals[size_t(ni[2])];
    if (glm::dot(blend, blend) > 0.0f) {
      const Vec3 shading = glm::normalize(blend);
      hit.shading_normal = glm::dot(shading, hit.normal) < 0.0f ? -shading : shading;
    }
  }
  // PLACEHOLDER
  // report_unfinished_task("stage2.mesh.hit_record");
  // hit.point = ray.at(found.t);
  // hit.set_face_normal(ray, glm::normalize(glm::cross(v1 - v0, v2 - v0)));
  // END TASK
  return hit;
}

namespace {

// The hit record of a sphere or plane hit, whose point has been projected back onto the surface.
Hit surface_hit(const Ray& ray, float t, const SurfacePoint& surface, Vec3 outward_normal, int material, int shape) {
  Hit hit;
  hit.t = t;
  hit.point = surface.point;
  hit.point_error = surface.error;
  hit.set_face_normal(ray, outward_normal);
  hit.material = material;
  hit.primitive = shape;
  return hit;
}

}  // namespace

Hit WhittedScene::sphere_hit_record(const PrimitiveHit& found, const Ray& ray) const {
  const SphereEntry& entry = primitives_->spheres[size_t(found.sphere)];
  const SurfacePoint surface = sphere_point(ray.at(found.t), entry.sphere);
  return surface_hit(ray, found.t, surface, sphere_normal(entry.sphere, surface.point), entry.material, entry.shape);
}

std::optional<Hit> WhittedScene::closest_hit(const Ray& ray, Interval range) const {
  std::optional<Hit> closest;
  if (const std::optional<PrimitiveHit> found = aggregate_->closest_hit(ray, range)) {
    closest = found->sphere >= 0 ? sphere_hit_record(*found, ray) : triangle_hit_record(*found, ray);
    range.max = found->t;
  }
  for (const PlaneEntry& p : planes_)
    if (const auto t = intersect_plane(ray, p.plane, range)) {
      closest = surface_hit(ray, *t, plane_point(ray.at(*t), p.plane), p.plane.normal, p.material, p.shape);
      range.max = *t;
    }
  return closest;
}

bool WhittedScene::occluded(const Ray& ray, Interval range) const {
  for (const PlaneEntry& p : planes_)
    if (intersect_plane(ray, p.plane, range)) return true;
  return aggregate_->occluded(ray, range);
}

}  // namespace rt
