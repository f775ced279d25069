// Writes docs/charts/stage4-direct.csv, the data behind docs/charts/stage4-direct-error-vs-time.png:
// for a scene lit by a small emitter and the same scene lit by a large one (equal power), each of
// the four direct-lighting estimators (and light sampling with the rectangle lights sampled by
// solid angle) renders at 1, 2, 4, ... 256 samples per pixel; each render's
// wall time and its RMSE against a converged reference are recorded. Prints the time each
// estimator needs to reach a fixed error, as ratios to light sampling.
// Run through tools/make-charts.sh, or: build/release/bin/direct_error_vs_time OUT.csv
#include "04-radiometry/direct_lighting.h"
#include "01-ray-casting/render.h"
#include "common/metrics.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kWidth = 144, kHeight = 96;
constexpr int kReferenceSpp = 8192;

struct Setup {
  const char* name;
  const char* file;
};

Image render(const LightingScene& scene, const Camera& camera, DirectEstimator estimator, int spp,
             std::uint64_t seed, double* seconds = nullptr) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.spp = spp;
  settings.seed = seed;
  DirectOptions options;
  options.estimator = estimator;
  const auto start = Clock::now();
  Image image = render_image(camera, settings, 0, [&](const Ray& ray, Rng& rng) {
    return direct_radiance(scene, ray, options, rng);
  });
  if (seconds) *seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

// The reference: light sampling at kReferenceSpp on its own seed. Its RMSE is about a sixth of
// the best 256-spp render's (errors add in quadrature, so it inflates that one by under 2%); a
// BRDF-sampled half would have made it noisier, not better, under the small light.
Image reference(const LightingScene& scene, const Camera& camera) {
  return render(scene, camera, DirectEstimator::light, kReferenceSpp, 1000);
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  if (argc != 2) {
    std::fprintf(stderr, "usage: direct_error_vs_time OUT.csv\n");
    return 2;
  }
  std::ofstream csv(argv[1]);
  csv << "scene,estimator,spp,seconds,rmse\n";
  for (const Setup setup : {Setup{"small light", "assets/scenes/direct-small-light.json"},
                            Setup{"large light", "assets/scenes/direct-large-light.json"}}) {
    const SceneDescription description = load_scene(std::string(RT_SOURCE_DIR) + "/" + setup.file);
    const LightingScene scene(description);
    LightingOptions by_solid_angle;
    by_solid_angle.rectangle_sampling = RectangleSampling::solid_angle;
    const LightingScene solid_angle_scene(description, by_solid_angle);
    const Camera camera(description.camera, kWidth, kHeight);
    const Image truth = reference(scene, camera);
    std::printf("%s (reference: light sampling, %d spp)\n", setup.name, kReferenceSpp);
    struct Series {
      DirectEstimator estimator;
      const char* name;
      const LightingScene& sampled;  // the scene as built for this series' light sampling
    };
    for (const Series& series : {Series{DirectEstimator::uniform_hemisphere, "uniform", scene},
                                 Series{DirectEstimator::cosine_hemisphere, "cosine", scene},
                                 Series{DirectEstimator::brdf, "brdf", scene},
                                 Series{DirectEstimator::light, "light", scene},
                                 Series{DirectEstimator::light, "light (solid angle)", solid_angle_scene}}) {
      const auto& [estimator, name, sampled] = series;
      for (int spp = 1; spp <= 256; spp *= 2) {
        double seconds = 0.0;
        const Image image = render(sampled, camera, estimator, spp, 1, &seconds);
        const double error = rmse(image, truth);
        csv << setup.name << "," << name << "," << spp << "," << seconds << "," << error << "\n";
        if (spp == 256) std::printf("  %-19s 256 spp: %.3f s, RMSE %.5f\n", name, seconds, error);
      }
    }
  }
  return csv.good() ? 0 : 1;
}
