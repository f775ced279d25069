#include "02-whitted/whitted_scene.h"

#include "01-ray-casting/plane_intersection.h"
#include "01-ray-casting/sphere_intersection.h"
#include "02-whitted/mesh_instance.h"
#include "02-whitted/ray_offset.h"
#include "common/error.h"
#include "common/task.h"

namespace rt {
namespace {

// Meshes with fewer triangles than this are tested directly: a bounding sphere would cost as much
// as the triangles it saves.
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

WhittedScene::WhittedScene(const SceneDescription& description, TriangleMethod triangle_method)
    : triangle_method_(triangle_method),
      materials_(description.materials),
      lights_(description.lights),
      background_(description.background) {
  for (size_t i = 0; i < description.shapes.size(); ++i) {
    const Shape& shape = description.shapes[i];
    const int index = int(i);
    auto add_mesh = [&](TriangleMesh mesh) {
      std::optional<Sphere> bound;
      if (mesh.triangles.size() >= kBoundingSphereMinTriangles) bound = bounding_sphere(mesh);
      meshes_.push_back({std::move(mesh), bound, shape.material, index});
    };
    if (const auto* sphere = std::get_if<Sphere>(&shape.geometry))
      spheres_.push_back({*sphere, shape.material, index});
    else if (const auto* plane = std::get_if<Plane>(&shape.geometry))
      planes_.push_back({*plane, shape.material, index});
    else if (const auto* triangle = std::get_if<Triangle>(&shape.geometry))
      add_mesh(mesh_from_triangle(*triangle));
    else if (const auto* quad = std::get_if<Quad>(&shape.geometry))
      add_mesh(mesh_from_quad(*quad));
    else if (const auto* mesh = std::get_if<Mesh>(&shape.geometry))
      add_mesh(place_mesh(*mesh->mesh, mesh->transform));
    else
      throw InputError(description.source + ": /shapes/" + std::to_string(i) +
                       ": stage 2 renders spheres, planes, triangles, quads and meshes (tori are "
                       "stage 1's implicit surfaces)");
  }
}

bool WhittedScene::misses_bound(const MeshEntry& entry, const Ray& ray, Interval range) {
  if (!entry.bound) return false;
  const std::optional<Interval> span = sphere_span(ray, *entry.bound);
  return !span || span->max <= range.min || span->min >= range.max;
}

size_t WhittedScene::triangle_count() const {
  size_t count = 0;
  for (const MeshEntry& entry : meshes_) count += entry.mesh.triangles.size();
  return count;
}

std::optional<std::pair<TriangleHit, int>> WhittedScene::nearest_triangle(const MeshEntry& entry,
                                                                          const Ray& ray,
                                                                          Interval range) const {
  if (misses_bound(entry, ray, range)) return std::nullopt;
  std::optional<std::pair<TriangleHit, int>> nearest;
  const auto& p = entry.mesh.positions;
  for (size_t k = 0; k < entry.mesh.triangles.size(); ++k) {
    const auto& c = entry.mesh.triangles[k];
    if (const auto hit = intersect_triangle(triangle_method_, ray, p[c[0]], p[c[1]], p[c[2]], range)) {
      nearest = {*hit, int(k)};
      range.max = hit->t;
    }
  }
  return nearest;
}

Hit WhittedScene::triangle_hit_record(const MeshEntry& entry, int triangle, const TriangleHit& found,
                                      const Ray& ray) const {
  const TriangleMesh& mesh = entry.mesh;
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

std::optional<Hit> WhittedScene::closest_hit(const Ray& ray, Interval range) const {
  std::optional<Hit> closest;
  auto record = [&](float t, const SurfacePoint& surface, Vec3 outward_normal, int material, int shape) {
    Hit hit;
    hit.t = t;
    hit.point = surface.point;
    hit.point_error = surface.error;
    hit.set_face_normal(ray, outward_normal);
    hit.material = material;
    hit.primitive = shape;
    closest = hit;
    range.max = t;
  };
  for (const SphereEntry& s : spheres_)
    if (const auto t = intersect_sphere_stable(ray, s.sphere, range)) {
      const SurfacePoint surface = sphere_point(ray.at(*t), s.sphere);
      record(*t, surface, sphere_normal(s.sphere, surface.point), s.material, s.shape);
    }
  for (const PlaneEntry& p : planes_)
    if (const auto t = intersect_plane(ray, p.plane, range))
      record(*t, plane_point(ray.at(*t), p.plane), p.plane.normal, p.material, p.shape);
  for (const MeshEntry& entry : meshes_)
    if (const auto found = nearest_triangle(entry, ray, range)) {
      closest = triangle_hit_record(entry, found->second, found->first, ray);
      range.max = found->first.t;
    }
  return closest;
}

bool WhittedScene::occluded(const Ray& ray, Interval range) const {
  for (const SphereEntry& s : spheres_)
    if (intersect_sphere_stable(ray, s.sphere, range)) return true;
  for (const PlaneEntry& p : planes_)
    if (intersect_plane(ray, p.plane, range)) return true;
  for (const MeshEntry& entry : meshes_) {
    if (misses_bound(entry, ray, range)) continue;
    const auto& p = entry.mesh.positions;
    for (const auto& c : entry.mesh.triangles)
      if (intersect_triangle(triangle_method_, ray, p[c[0]], p[c[1]], p[c[2]], range)) return true;
  }
  return false;
}

}  // namespace rt
