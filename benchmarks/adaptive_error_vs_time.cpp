// Writes docs/charts/stage5-adaptive.csv, the data behind docs/charts/stage5-adaptive.png, and the
// sample-count heat maps docs/images/stage5-adaptive-map-*.png: stage 5's path tracer (MIS, Sobol)
// with the same number of paths in every pixel (1, 2, 4, ... spp) and adaptively (tolerance 0.4,
// 0.2, ... with at most 1024 paths a pixel), on two scenes: the Cornell box (256 x 256, against
// the stored reference) and assets/scenes/environment.json (192 x 108, against a uniform render
// of 8192 paths a pixel on its own seed), whose sky is trivial and whose glossy balls are hard.
// Each render's wall time and RMSE are recorded; the heat maps are of tolerance 0.1.
// Run through tools/make-charts.sh (about 6 minutes on 2 cores), or:
//   build/release/bin/adaptive_error_vs_time OUT.csv IMAGE_FOLDER
#include "05-path-tracing/path_render.h"
#include "common/heat_map.h"
#include "common/image_io.h"
#include "common/metrics.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMostPaths = 1024;

struct Setup {
  const char* name;
  SceneDescription description;
  int width, height;
  Image reference;
};

SampleSums render(const Setup& setup, const LightingScene& scene, int spp, const AdaptiveSettings* adaptive,
                  std::uint64_t seed, double& seconds) {
  RenderSettings settings;
  settings.width = setup.width;
  settings.height = setup.height;
  settings.spp = spp;
  settings.seed = seed;
  PathOptions options;
  options.max_depth = setup.description.render.max_depth;
  const Camera camera(setup.description.camera, setup.width, setup.height);
  SampleGuard guard;
  const auto start = Clock::now();
  SampleSums sums = render_path_samples(scene, camera, settings, options, SamplerKind::sobol, 0, guard, nullptr, adaptive);
  seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return sums;
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  if (argc != 3 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: adaptive_error_vs_time OUT.csv IMAGE_FOLDER\n");
    return 2;
  }
  const std::string root = RT_SOURCE_DIR;
  Setup setups[2] = {
      {"cornell-box", load_scene(root + "/assets/scenes/cornell-box.json"), 256, 256,
       read_pfm(root + "/assets/references/cornell-box-256.pfm")},
      {"environment", load_scene(root + "/assets/scenes/environment.json"), 192, 108, Image{}},
  };
  std::ofstream csv(argv[1]);
  csv << "scene,method,parameter,mean_spp,seconds,rmse\n";
  for (Setup& setup : setups) {
    const LightingScene scene(setup.description);
    double seconds = 0.0;
    if (setup.reference.width() == 0) setup.reference = render(setup, scene, 8192, nullptr, 1000, seconds).mean();
    const double pixels = double(setup.width) * double(setup.height);
    std::printf("%s:\n", setup.name);
    for (int spp = 4; spp <= kMostPaths; spp *= 2) {
      const SampleSums sums = render(setup, scene, spp, nullptr, 1, seconds);
      const double error = rmse(sums.mean(), setup.reference);
      csv << setup.name << ",uniform," << spp << "," << spp << "," << seconds << "," << error << "\n";
      std::printf("  uniform  %5d spp            %7.2f s  RMSE %.4f\n", spp, seconds, error);
    }
    for (const float tolerance : {0.4f, 0.2f, 0.1f, 0.05f, 0.025f}) {
      AdaptiveSettings adaptive;
      adaptive.tolerance = tolerance;
      const SampleSums sums = render(setup, scene, kMostPaths, &adaptive, 1, seconds);
      const double error = rmse(sums.mean(), setup.reference), mean_spp = double(sums.total_count()) / pixels;
      csv << setup.name << ",adaptive," << tolerance << "," << mean_spp << "," << seconds << "," << error << "\n";
      std::printf("  adaptive %5.3f (%6.1f spp)  %7.2f s  RMSE %.4f\n", tolerance, mean_spp, seconds, error);
      if (tolerance == 0.1f)
        write_image(std::filesystem::path(argv[2]) / (std::string("stage5-adaptive-map-") + setup.name + ".png"),
                    heat_map(sums.counts(), sums.width(), sums.height(), kMostPaths));
    }
    std::fflush(stdout);
  }
  return csv.good() ? 0 : 1;
}
