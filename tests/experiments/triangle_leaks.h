// Stage 2: the watertightness experiment behind docs/stage2.md's leak table and the test
// Watertight.*: rays from inside a closed mesh aimed exactly at its shared edges and vertices.
// Every such ray must hit some triangle; one that hits none has leaked through a crack.
#pragma once

#include "02-whitted/triangle_ray.h"
#include "common/triangle_mesh.h"

#include <cstdint>
#include <vector>

namespace rt {

struct LeakSetup {
  TriangleMesh mesh;            // a jittered, closed UV sphere, scaled and moved off the origin
  std::vector<Ray> edge_rays;   // aimed at points on shared edges
  std::vector<Ray> vertex_rays; // aimed at vertices
};

// The mesh is make_uv_sphere(12, 24, 0.3) times `scale`, translated by 0.37 * scale on every axis
// so that no coordinate is round. Each shared edge gets `rays_per_edge` targets lerp(a, b, s) with
// s uniform in (0, 1), each vertex one ray; origins are random points within 0.3 * scale of the
// centre.
LeakSetup make_leak_setup(float scale, int rays_per_edge, std::uint64_t seed);

// How many of `rays` hit no triangle of `mesh` at any t > 0 (every triangle tested, no culling).
int count_leaks(const TriangleMesh& mesh, const std::vector<Ray>& rays, TriangleMethod method);

}  // namespace rt
