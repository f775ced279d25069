// Writes docs/charts/stage4-environment.csv, the data behind docs/charts/stage4-environment.png:
// stage 4's light-sampling estimator on assets/scenes/environment.json (a sky with a small, bright
// sun), with the environment sampled by its luminance table and uniformly over the sphere, at 1,
// 2, 4, ... 256 samples per pixel; each render's wall time and RMSE against a converged reference
// (importance sampling at 4096 spp on its own seed). Prints the variance ratio per sample and the
// time each strategy needs to reach a fixed error.
// Run through tools/make-charts.sh (about a minute), or:
//   build/release/bin/environment_sampling OUT.csv
#include "01-ray-casting/render.h"
#include "04-radiometry/direct_lighting.h"
#include "common/metrics.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kWidth = 160, kHeight = 90;

Image render(const LightingScene& scene, const Camera& camera, int spp, std::uint64_t seed, double* seconds = nullptr) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.spp = spp;
  settings.seed = seed;
  const auto start = Clock::now();
  Image image = render_image(camera, settings, 0, [&](const Ray& ray, Rng& rng) {
    return direct_radiance(scene, ray, DirectOptions{}, rng);
  });
  if (seconds) *seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  if (argc != 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: environment_sampling OUT.csv\n");
    return 2;
  }
  const SceneDescription description = load_scene(std::string(RT_SOURCE_DIR) + "/assets/scenes/environment.json");
  const Camera camera(description.camera, kWidth, kHeight);
  LightingOptions uniform_options;
  uniform_options.environment_sampling = EnvironmentSampling::uniform;
  const LightingScene importance(description), uniform(description, uniform_options);
  const Image reference = render(importance, camera, 4096, 1000);

  std::ofstream csv(argv[1]);
  csv << "strategy,spp,seconds,rmse\n";
  // rmse^2 x spp estimates the variance of one sample (errors fall as 1 / sqrt(spp)): averaged
  // over the renders of 4 spp and more, one figure per strategy.
  double variance[2] = {0.0, 0.0};
  for (int s = 0; s < 2; ++s) {
    const LightingScene& scene = s == 0 ? importance : uniform;
    const char* name = s == 0 ? "importance" : "uniform";
    for (int spp = 1; spp <= 256; spp *= 2) {
      double seconds = 0.0;
      const double error = rmse(render(scene, camera, spp, 1, &seconds), reference);
      csv << name << "," << spp << "," << seconds << "," << error << "\n";
      if (spp >= 4) variance[s] += error * error * spp / 7.0;
    }
  }
  std::printf("environment.json, light sampling: variance per sample %.3g by importance, %.3g uniform (ratio %.0f)\n",
              variance[0], variance[1], variance[1] / variance[0]);
  return csv.good() ? 0 : 1;
}
