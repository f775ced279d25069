// Stage 1 timings: ray generation, the two sphere formulas, the torus's root finding, and a whole
// render. Run: build/release/bin/stage1_bench (add --benchmark_filter=Sphere to pick).
#include "01-ray-casting/camera_rays.h"
#include "01-ray-casting/implicit_surface.h"
#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "01-ray-casting/sphere_intersection.h"
#include "experiments/sphere_precision.h"

#include <benchmark/benchmark.h>

namespace rt {
namespace {

void BM_GenerateCameraRays(benchmark::State& state) {
  const Camera camera(CameraSpec{Vec3(0, 1, -5), Vec3(0), Vec3(0, 1, 0), 40.0f}, 640, 480);
  Rng rng(1, 0, 0);
  for (auto _ : state) {
    const Vec2 film(rng.uniform() * 640.0f, rng.uniform() * 480.0f);
    benchmark::DoNotOptimize(generate_camera_ray(camera, film));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GenerateCameraRays);

// The same 4096 rays (83% hits) for both formulas, at the distance given as the argument.
template <SphereIntersectFn Intersect>
void BM_Sphere(benchmark::State& state) {
  const FarSphereRays setup = make_far_sphere_rays(float(state.range(0)), 4096, 7);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Intersect(setup.rays[i], setup.sphere, Interval::positive()));
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Sphere<intersect_sphere_textbook>)->Name("BM_SphereTextbook")->Arg(10)->Arg(10000);
BENCHMARK(BM_Sphere<intersect_sphere_stable>)->Name("BM_SphereStable")->Arg(10)->Arg(10000);

void BM_TorusRootFinding(benchmark::State& state) {
  const TorusSurface torus(Torus{Vec3(0), Vec3(0, 1, 0), 2.0f, 0.5f});
  Rng rng(3, 0, 0);
  std::vector<Ray> rays;
  for (int i = 0; i < 4096; ++i) {
    const Vec3 target(rng.uniform() * 6 - 3, rng.uniform() - 0.5f, rng.uniform() * 6 - 3);
    rays.push_back(Ray{Vec3(0, 3, -8), glm::normalize(target - Vec3(0, 3, -8))});
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(intersect_implicit(torus, rays[i], Interval::positive()));
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TorusRootFinding);

// The whole spheres scene at 160 x 100, 1 spp, on one thread: camera rays, shading, shadow rays.
void BM_RenderSpheresScene(benchmark::State& state) {
  const SceneDescription description = load_scene(RT_SOURCE_DIR "/assets/scenes/spheres.json");
  const RayCastingScene scene(description);
  RenderSettings settings = description.render;
  settings.width = 160;
  settings.height = 100;
  settings.spp = 1;
  const Camera camera(description.camera, settings.width, settings.height);
  for (auto _ : state)
    benchmark::DoNotOptimize(render_image(camera, settings, 1, [&](const Ray& ray, Rng&) {
      return cast_ray(scene, ray);
    }));
  state.SetItemsProcessed(state.iterations() * settings.width * settings.height);
  state.SetLabel("items = camera rays");
}
BENCHMARK(BM_RenderSpheresScene)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rt
