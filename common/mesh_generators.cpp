#include "common/random.h"
#include "common/triangle_mesh.h"

namespace rt {

TriangleMesh make_uv_sphere(int rings, int segments, float jitter, std::uint64_t seed) {
  TriangleMesh mesh;
  Rng rng(seed, 0, 0);
  auto add_vertex = [&](float theta, float phi) {
    const float radius = 1.0f + jitter * rng.uniform();
    mesh.positions.push_back(radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                           std::sin(theta) * std::sin(phi)));
    return std::uint32_t(mesh.positions.size() - 1);
  };
  // Orients every triangle outwards; the mesh is star-shaped about the origin, so the side its
  // centroid lies on decides.
  auto add_triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vec3 pa = mesh.positions[a], pb = mesh.positions[b], pc = mesh.positions[c];
    if (glm::dot(glm::cross(pb - pa, pc - pa), pa + pb + pc) < 0.0f) std::swap(b, c);
    mesh.triangles.push_back({a, b, c});
  };

  const std::uint32_t north = add_vertex(0.0f, 0.0f);
  std::vector<std::uint32_t> ring_start;
  for (int i = 1; i < rings; ++i) {
    ring_start.push_back(std::uint32_t(mesh.positions.size()));
    for (int j = 0; j < segments; ++j) add_vertex(kPi * float(i) / float(rings), 2.0f * kPi * float(j) / float(segments));
  }
  const std::uint32_t south = add_vertex(kPi, 0.0f);

  auto at = [&](int ring, int segment) { return ring_start[size_t(ring)] + std::uint32_t(segment % segments); };
  for (int j = 0; j < segments; ++j) {
    add_triangle(north, at(0, j), at(0, j + 1));
    for (int i = 0; i + 1 < rings - 1; ++i) {
      add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
    add_triangle(south, at(rings - 2, j + 1), at(rings - 2, j));
  }
  return mesh;
}

}  // namespace rt
