// An indexed triangle mesh, as an OBJ file or a generator gives it. Positions and normals are
// indexed separately, as in OBJ, so a vertex may carry different normals on either side of a crease.
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

  bool has_normals(size_t triangle) const {
    return !triangle_normals.empty() && triangle_normals[triangle][0] >= 0;
  }
};

// Closed test meshes. A UV sphere of `rings` x `segments` quads (two triangles each, fans at the
// poles) whose vertices sit at radius 1 + jitter * u, u uniform in [0, 1) from `seed`: shared
// edges and vertices are exact, so a watertight intersector lets no ray through, and the jitter
// makes the coordinates anything but round numbers.
TriangleMesh make_uv_sphere(int rings, int segments, float jitter, std::uint64_t seed);

}  // namespace rt
