#include "02-whitted/mesh_instance.h"

#include "common/task.h"

#include <glm/matrix.hpp>

namespace rt {

glm::mat3 normal_matrix(const glm::mat3& linear) {
  // BEGIN TASK stage2.mesh.normal_matrix
  return glm::transpose(glm::inverse(linear));
  // PLACEHOLDER
  // report_unfinished_task("stage2.mesh.normal_matrix");
  // return linear;  // right for rotations and uniform scales only
  // END TASK
}

TriangleMesh place_mesh(const TriangleMesh& mesh, const Transform& transform) {
  TriangleMesh world = mesh;
  for (Vec3& p : world.positions) p = transform.point(p);
  const glm::mat3 normals = normal_matrix(transform.linear());
  for (Vec3& n : world.normals) n = glm::normalize(normals * n);
  if (glm::determinant(transform.linear()) < 0.0f) {
    for (auto& corners : world.triangles) std::swap(corners[1], corners[2]);
    for (auto& corners : world.triangle_normals) std::swap(corners[1], corners[2]);
    for (auto& corners : world.triangle_uvs) std::swap(corners[1], corners[2]);
  }
  return world;
}

TriangleMesh mesh_from_triangle(const Triangle& triangle) {
  TriangleMesh mesh;
  mesh.positions.assign(triangle.vertices.begin(), triangle.vertices.end());
  mesh.triangles = {{0, 1, 2}};
  mesh.uvs.assign(triangle.uvs.begin(), triangle.uvs.end());
  mesh.triangle_uvs = {{0, 1, 2}};
  return mesh;
}

TriangleMesh mesh_from_quad(const Quad& quad) {
  TriangleMesh mesh;
  mesh.positions.assign(quad.vertices.begin(), quad.vertices.end());
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.uvs.assign(quad.uvs.begin(), quad.uvs.end());
  mesh.triangle_uvs = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

std::optional<TriangleMesh> triangles_of(const Geometry& geometry) {
  if (const auto* triangle = std::get_if<Triangle>(&geometry)) return mesh_from_triangle(*triangle);
  if (const auto* quad = std::get_if<Quad>(&geometry)) return mesh_from_quad(*quad);
  if (const auto* mesh = std::get_if<Mesh>(&geometry)) return place_mesh(*mesh->mesh, mesh->transform);
  return std::nullopt;
}

}  // namespace rt
