#include "02-whitted/triangle_kind.h"

#include "02-whitted/mesh_instance.h"
#include "02-whitted/ray_offset.h"
#include "common/task.h"

namespace rt {

void TriangleKind::Store::add_mesh(TriangleMesh mesh, int material, int shape) {
  first.push_back(std::uint32_t(mesh_of.size()));
  mesh_of.insert(mesh_of.end(), mesh.triangles.size(), std::uint32_t(meshes.size()));
  meshes.push_back({std::move(mesh), material, shape});
}

bool TriangleKind::add(Store& store, const Shape& shape, int index) {
  std::optional<TriangleMesh> mesh = triangles_of(shape.geometry);
  if (mesh) store.add_mesh(std::move(*mesh), shape.material, index);
  return mesh.has_value();
}

std::vector<PrimitiveRun> TriangleKind::runs(const Store& store) {
  std::vector<PrimitiveRun> runs;
  for (size_t m = 0; m < store.meshes.size(); ++m)
    runs.push_back({store.first[m], store.first[m] + std::uint32_t(store.meshes[m].geometry.triangles.size())});
  return runs;
}

Hit TriangleKind::hit_record(const Store& store, const PrimitiveHit& found, const Ray& ray) {
  const std::uint32_t m = store.mesh_of[found.index];
  const Placed<TriangleMesh>& placed = store.meshes[m];
  const size_t triangle = found.index - store.first[m];
  const TriangleCorners corners = hot(store, found.index);
  const Vec3 v0 = corners.corner(0), v1 = corners.corner(1), v2 = corners.corner(2);
  // BEGIN TASK stage2.mesh.hit_record
  const TriangleMesh& mesh = placed.geometry;
  const Vec3 b(1.0f - found.b1 - found.b2, found.b1, found.b2);
  const SurfacePoint surface = triangle_point(b, v0, v1, v2);
  Hit hit = make_hit(ray, found.t, surface.point, surface.error, glm::normalize(glm::cross(v1 - v0, v2 - v0)),
                     placed.material, placed.shape);
  if (mesh.has_normals(triangle)) {
    // Phong-style normal interpolation: the barycentric blend of the vertex normals, turned to the
    // side the ray came from like the geometric normal.
    const auto& ni = mesh.triangle_normals[triangle];
    const Vec3 blend = b.x * mesh.normals[size_t(ni[0])] + b.y * mesh.normals[size_t(ni[1])] +
                       b.z * mesh.normals[size_t(ni[2])];
    if (glm::dot(blend, blend) > 0.0f) {
      const Vec3 shading = glm::normalize(blend);
      hit.shading_normal = glm::dot(shading, hit.normal) < 0.0f ? -shading : shading;
    }
  }
  // PLACEHOLDER
  // report_unfinished_task("stage2.mesh.hit_record");
  // Hit hit = make_hit(ray, found.t, ray.at(found.t), Vec3(0.0f), glm::normalize(glm::cross(v1 - v0, v2 - v0)),
  //                    placed.material, placed.shape);
  // END TASK
  hit.uv = placed.geometry.uv_at(triangle, found.b1, found.b2);
  hit.triangle = int(triangle);
  return hit;
}

}  // namespace rt
