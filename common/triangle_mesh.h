// An indexed triangle mesh, as an OBJ file or a generator gives it. Positions, normals and texture
// coordinates are indexed separately, as in OBJ, so a vertex may carry different normals on either
// side of a crease and different texture coordinates on either side of a seam.
#pragma once

#include "common/math.h"

#include <array>
#include <cstdint>
#include <vector>

namespace rt {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // unit vertex normals; may be empty
  // Corners of each triangle, counter-clockwise seen from outside: the outward normal is
  // (p1 - p0) x (p2 - p0).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Per triangle, the normal index of each corner; empty when the mesh has no normals, and
  // {-1, -1, -1} for a triangle whose corners do not all have one (it is shaded flat).
  std::vector<std::array<std::int32_t, 3>> triangle_normals;

  // Texture coordinates (u, v), and per triangle the index of each corner's, like the normals.
  std::vector<Vec2> uvs;
  std::vector<std::array<std::int32_t, 3>> triangle_uvs;

  bool has_normals(size_t triangle) const {
    return !triangle_normals.empty() && triangle_normals[triangle][0] >= 0;
  }
  bool has_uvs(size_t triangle) const { return !triangle_uvs.empty() && triangle_uvs[triangle][0] >= 0; }

  // The texture coordinates at barycentrics (b1, b2) of a triangle: the barycentric blend of its
  // corners' (u, v), or (b1, b2) itself when it has none, as if its corners were (0, 0), (1, 0),
  // (0, 1).
  Vec2 uv_at(size_t triangle, float b1, float b2) const {
    if (!has_uvs(triangle)) return Vec2(b1, b2);
    const auto& t = triangle_uvs[triangle];
    return (1.0f - b1 - b2) * uvs[size_t(t[0])] + b1 * uvs[size_t(t[1])] + b2 * uvs[size_t(t[2])];
  }
};

// Closed test meshes. A UV sphere of `rings` x `segments` quads (two triangles each, fans at the
// poles) whose vertices sit at radius 1 + jitter * u, u uniform in [0, 1) from `seed`: shared
// edges and vertices are exact, so a watertight intersector lets no ray through, and the jitter
// makes the coordinates anything but round numbers.
TriangleMesh make_uv_sphere(int rings, int segments, float jitter, std::uint64_t seed);

}  // namespace rt
