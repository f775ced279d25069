// Stage 2: triangles as a primitive kind (the contract: 02-whitted/primitives.h). A scene file's
// triangles, quads and OBJ meshes all become world-space triangle meshes (02-whitted/mesh_instance.h);
// the kind numbers their triangles one after another, mesh by mesh.
#pragma once

#include "02-whitted/primitives.h"


namespace rt {

struct TriangleKind {
  struct Store {
    std::vector<Placed<TriangleMesh>> meshes;  // in world space
    std::vector<std::uint32_t> first;          // per mesh: the kind's number of its first triangle
    std::vector<std::uint32_t> mesh_of;        // per triangle: its mesh
    TriangleMethod method = TriangleMethod::watertight;

    void add_mesh(TriangleMesh mesh, int material, int shape);
    // What the meshes take for intersecting: positions, corner numbers, and each triangle's mesh
    // (the vertex normals, which only shading reads, left out). Stage 3 counts it with its BVH.
    size_t bytes() const {
      size_t total = mesh_of.size() * sizeof(mesh_of[0]);
      for (const Placed<TriangleMesh>& m : meshes)
        total += m.geometry.positions.size() * sizeof(m.geometry.positions[0]) +
                 m.geometry.triangles.size() * sizeof(m.geometry.triangles[0]);
      return total;
    }
  };
  using Hot = TriangleCorners;  // the corners, copied out of the mesh axis by axis

  static bool add(Store& store, const Shape& shape, int index);
  static size_t size(const Store& store) { return store.mesh_of.size(); }
  static Hot hot(const Store& store, size_t i) {
    const std::uint32_t m = store.mesh_of[i];
    const TriangleMesh& mesh = store.meshes[m].geometry;
    const auto& c = mesh.triangles[i - store.first[m]];
    return TriangleCorners(mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]);
  }
  static Aabb bounds(const Hot& triangle) {
    Aabb box;
    for (int i = 0; i < 3; ++i) box.expand(triangle.corner(i));
    return box;
  }
  // Always inlined, so that a BVH's leaf loop holds the whole test (left to itself, GCC stops
  // inlining it once the watertight test is inlined into it).
  [[gnu::always_inline]] static std::optional<PrimitiveHit> intersect(const Store& store, const Hot& triangle,
                                                                      const TriangleRay& ray, Interval range) {
    // Each test's result converted on its own branch: merging the optionals first passes the hit
    // through memory, written in pieces and read back at once, which stalls the load (a failed
    // store-to-load forward; docs/stage5.md, the speed ladder).
    if (store.method == TriangleMethod::watertight_lanes) {
      if (const std::optional<TriangleHit> hit = intersect_triangle_lanes(ray.watertight, ray.lanes, triangle, range))
        return PrimitiveHit{hit->t, hit->b1, hit->b2};
      return std::nullopt;
    }
    const Vec3 v0 = triangle.corner(0), v1 = triangle.corner(1), v2 = triangle.corner(2);
    if (store.method == TriangleMethod::watertight) {
      if (const std::optional<TriangleHit> hit = intersect_triangle_watertight(ray.watertight, v0, v1, v2, range))
        return PrimitiveHit{hit->t, hit->b1, hit->b2};
      return std::nullopt;
    }
    if (const std::optional<TriangleHit> hit = intersect_triangle_moller_trumbore(ray.ray, v0, v1, v2, range))
      return PrimitiveHit{hit->t, hit->b1, hit->b2};
    return std::nullopt;
  }
  // Task stage2.mesh.hit_record (triangle_kind.cpp).
  static Hit hit_record(const Store& store, const PrimitiveHit& found, const Ray& ray);
  // One run per mesh: stage 2 tests a mesh's triangles only when the ray meets its bounding sphere.
  static std::vector<PrimitiveRun> runs(const Store& store);
};

}  // namespace rt
