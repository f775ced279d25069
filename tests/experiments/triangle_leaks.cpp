#include "experiments/triangle_leaks.h"

#include "common/random.h"

#include <set>
#include <utility>

namespace rt {

LeakSetup make_leak_setup(float scale, int rays_per_edge, std::uint64_t seed) {
  LeakSetup setup;
  setup.mesh = make_uv_sphere(12, 24, 0.3f, seed);
  const Vec3 centre(0.37f * scale);
  for (Vec3& p : setup.mesh.positions) p = p * scale + centre;

  Rng rng(seed, 1, 0);
  auto ray_to = [&](Vec3 target) {
    const Vec3 jitter = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
    const Vec3 origin = centre + (0.3f / std::sqrt(3.0f) * scale) * jitter;
    return Ray{origin, glm::normalize(target - origin)};
  };

  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : setup.mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[size_t(k)], t[size_t((k + 1) % 3)]));
  for (const auto& [a, b] : edges)
    for (int i = 0; i < rays_per_edge; ++i) {
      const float s = rng.uniform();
      const Vec3 pa = setup.mesh.positions[a], pb = setup.mesh.positions[b];
      setup.edge_rays.push_back(ray_to(pa + s * (pb - pa)));
    }
  for (const Vec3& p : setup.mesh.positions) setup.vertex_rays.push_back(ray_to(p));
  return setup;
}

int count_leaks(const TriangleMesh& mesh, const std::vector<Ray>& rays, TriangleMethod method) {
  int leaks = 0;
  for (const Ray& ray : rays) {
    bool hit = false;
    for (const auto& c : mesh.triangles) {
      const auto& p = mesh.positions;
      if (intersect_triangle(method, ray, p[c[0]], p[c[1]], p[c[2]], Interval::positive())) {
        hit = true;
        break;
      }
    }
    leaks += hit ? 0 : 1;
  }
  return leaks;
}

}  // namespace rt
