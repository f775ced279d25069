// A camera subpath through a random pixel of a 64 x 48 film and a light subpath, both from
// Rng(seed, 0, k), without Russian roulette: the real subpaths the weight tests of stages 6 and 7
// check their bookkeeping on.
#pragma once

#include "01-ray-casting/camera_rays.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "stage6/loaded_scene.h"

namespace rt::testing {

struct Subpaths {
  std::vector<PathVertex> camera, light;
};

inline Subpaths random_subpaths(const LoadedScene& s, std::uint64_t seed, std::uint64_t k, int max_vertices = 6) {
  Rng rng(seed, 0, k);
  Subpaths p;
  const Ray ray = generate_camera_ray(s.camera, Vec2(rng.uniform() * 64.0f, rng.uniform() * 48.0f));
  p.camera.push_back(camera_vertex(s.camera));
  WalkSettings walk;
  walk.max_vertices = max_vertices;
  walk.roulette_start = 100;  // every walk runs to max_vertices or until it leaves the scene
  random_walk(s.scene, ray, Color(1.0f), camera_direction_pdf(s.camera, ray.direction), walk, rng, p.camera);
  if (const std::optional<LightSubpathStart> start = start_light_subpath(s.scene, rng, walk.offset)) {
    p.light.push_back(start->origin);
    walk.mode = TransportMode::importance;
    random_walk(s.scene, start->ray, start->beta, start->pdf_w, walk, rng, p.light);
  }
  return p;
}

}  // namespace rt::testing
