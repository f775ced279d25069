// Stage 2 timings: the triangle tests on the same rays, and whole renders of the Whitted scene
// and the point-lit Cornell box. Run: build/release/bin/stage2_bench
#include "01-ray-casting/render.h"
#include "experiments/triangle_leaks.h"
#include "02-whitted/triangle_kind.h"
#include "02-whitted/whitted.h"
#include "common/random.h"

#include <benchmark/benchmark.h>

namespace rt {
namespace {

// 4096 (ray, triangle) pairs from the crack experiment's jittered sphere mesh
// (stages/experiments/triangle_leaks.h). `all_hit`: each ray is aimed at its triangle's centroid.
// Otherwise each ray (aimed at some shared edge) meets a random triangle, which it almost always
// misses, as most tests in a brute-force loop do.
struct TrianglePairs {
  std::vector<Ray> rays;
  std::vector<std::array<Vec3, 3>> triangles;
};

TrianglePairs make_pairs(bool all_hit) {
  const LeakSetup setup = make_leak_setup(1.0f, 2, 7);
  const TriangleMesh& mesh = setup.mesh;
  TrianglePairs pairs;
  Rng rng(9, 0, 0);
  for (size_t i = 0; i < 4096; ++i) {
    const auto& c = mesh.triangles[size_t(rng.uniform() * float(mesh.triangles.size()))];
    const std::array<Vec3, 3> v{mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]};
    pairs.triangles.push_back(v);
    if (all_hit) {
      const Vec3 origin(0.37f), centroid = (v[0] + v[1] + v[2]) / 3.0f;
      pairs.rays.push_back(Ray{origin, glm::normalize(centroid - origin)});
    } else {
      pairs.rays.push_back(setup.edge_rays[i % setup.edge_rays.size()]);
    }
  }
  return pairs;
}

// Times test(i) for the 4096 pairs in turn, and reports the share that hit.
template <class Test>
void time_pairs(benchmark::State& state, Test&& test) {
  size_t i = 0, hits = 0;
  for (auto _ : state) {
    const auto hit = test(i);
    hits += hit ? 1 : 0;
    benchmark::DoNotOptimize(hit);
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = double(hits) / double(state.iterations());
}

template <TriangleMethod Method, bool AllHit>
void BM_Triangle(benchmark::State& state) {
  const TrianglePairs pairs = make_pairs(AllHit);
  time_pairs(state, [&](size_t i) {
    const auto& v = pairs.triangles[i];
    return intersect_triangle(Method, pairs.rays[i], v[0], v[1], v[2], Interval::positive());
  });
}
BENCHMARK(BM_Triangle<TriangleMethod::moller_trumbore, false>)->Name("BM_TriangleMostlyMissesMollerTrumbore");
BENCHMARK(BM_Triangle<TriangleMethod::watertight, false>)->Name("BM_TriangleMostlyMissesWatertight");
BENCHMARK(BM_Triangle<TriangleMethod::moller_trumbore, true>)->Name("BM_TriangleAllHitMollerTrumbore");
BENCHMARK(BM_Triangle<TriangleMethod::watertight, true>)->Name("BM_TriangleAllHitWatertight");
BENCHMARK(BM_Triangle<TriangleMethod::watertight_lanes, false>)->Name("BM_TriangleMostlyMissesWatertightLanes");
BENCHMARK(BM_Triangle<TriangleMethod::watertight_lanes, true>)->Name("BM_TriangleAllHitWatertightLanes");

// The same pairs as a BVH's leaf loop meets them: each ray prepared once beforehand (TriangleRay)
// and each triangle stored as its kind stores it (TriangleCorners), so only the test is timed, as
// TriangleKind::intersect calls it. The lanes pay here; in the loop above their per-ray broadcast
// and the corners' transposition, made anew for every pair, cost more than they save.
template <TriangleMethod Method, bool AllHit>
void BM_TriangleInLeaf(benchmark::State& state) {
  const TrianglePairs pairs = make_pairs(AllHit);
  std::vector<TriangleRay> rays;
  std::vector<TriangleCorners> triangles;
  for (size_t k = 0; k < pairs.rays.size(); ++k) {
    rays.emplace_back(pairs.rays[k]);
    const auto& v = pairs.triangles[k];
    triangles.emplace_back(v[0], v[1], v[2]);
  }
  TriangleKind::Store store;
  store.method = Method;
  time_pairs(state, [&](size_t i) { return TriangleKind::intersect(store, triangles[i], rays[i], Interval::positive()); });
}
BENCHMARK(BM_TriangleInLeaf<TriangleMethod::watertight, false>)->Name("BM_TriangleInLeafMostlyMissesWatertight");
BENCHMARK(BM_TriangleInLeaf<TriangleMethod::watertight_lanes, false>)->Name("BM_TriangleInLeafMostlyMissesLanes");
BENCHMARK(BM_TriangleInLeaf<TriangleMethod::watertight, true>)->Name("BM_TriangleInLeafAllHitWatertight");
BENCHMARK(BM_TriangleInLeaf<TriangleMethod::watertight_lanes, true>)->Name("BM_TriangleInLeafAllHitLanes");

// A whole scene at 160 x 100 (Whitted) or 100 x 100 (Cornell), 1 spp, one thread.
void render_scene(benchmark::State& state, const char* file, int width, int height) {
  const SceneDescription description = load_scene(std::string(RT_SOURCE_DIR) + "/" + file);
  const WhittedScene scene(description);
  RenderSettings settings = description.render;
  settings.width = width;
  settings.height = height;
  settings.spp = 1;
  WhittedOptions options;
  options.max_depth = settings.max_depth;
  const Camera camera(description.camera, width, height);
  for (auto _ : state)
    benchmark::DoNotOptimize(render_image(camera, settings, 1, [&](const Ray& ray, Rng&) {
      return whitted_radiance(scene, ray, options);
    }));
  state.SetItemsProcessed(state.iterations() * width * height);
  state.SetLabel("items = camera rays");
}
void BM_RenderWhittedScene(benchmark::State& state) { render_scene(state, "assets/scenes/whitted.json", 160, 100); }
void BM_RenderCornellPointLight(benchmark::State& state) {
  render_scene(state, "assets/scenes/cornell-box-point-light.json", 100, 100);
}
BENCHMARK(BM_RenderWhittedScene)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderCornellPointLight)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rt
