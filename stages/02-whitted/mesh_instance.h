// Stage 2: turning a scene file's triangles, quads and OBJ meshes into world-space triangle meshes.
#pragma once

#include "common/scene.h"
#include "common/triangle_mesh.h"

#include <glm/mat3x3.hpp>

#include <optional>

namespace rt {

// Task stage2.mesh.normal_matrix. Normals do not transform like positions. A normal n must stay
// perpendicular to every tangent t, and tangents map by the linear part M: t' = M t. Asking
// n'.t' = 0 whenever n.t = 0 gives n' = (M^-1)^T n, the inverse transpose. For rotations it equals
// M; under a non-uniform scale M itself tilts normals the wrong way (the test squashes a sphere).
glm::mat3 normal_matrix(const glm::mat3& linear);

// A world-space copy of `mesh`: positions through the transform, normals through its normal
// matrix (renormalized). A transform with det M < 0 (a mirroring scale) turns counter-clockwise
// triangles clockwise, so two corners of every triangle are swapped to keep the outward side out.
TriangleMesh place_mesh(const TriangleMesh& mesh, const Transform& transform);

// One triangle, and a quad meshed as (v0, v1, v2) + (v0, v2, v3) (docs/design.md): exact for a planar
// parallelogram, and the definition of the surface when the four corners are not coplanar.
TriangleMesh mesh_from_triangle(const Triangle& triangle);
TriangleMesh mesh_from_quad(const Quad& quad);

// The world-space triangles of a triangle, quad or mesh shape; nothing for other shapes.
std::optional<TriangleMesh> triangles_of(const Geometry& geometry);

}  // namespace rt
