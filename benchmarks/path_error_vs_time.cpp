// Writes docs/charts/stage5-paths.csv, the data behind docs/charts/stage5-error-vs-time.png and
// docs/charts/stage5-convergence.png, and prints the figures quoted in docs/stage5.md:
//  1. throughput: paths per second on the 256 x 256 Cornell box (MIS, Sobol) with 1 and 2 threads,
//     the best of three runs each;
//  2. error against time: each integrator (and MIS with independent numbers) renders at 1, 2, 4, ...
//     spp, recording wall time and RMSE against the converged reference, until the error is below
//     0.004 or one render takes over 60 s; then the time each one needs to reach RMSE 0.02, 0.01
//     and 0.005, interpolated on the log-log line between the two renders around it.
// Run through tools/make-charts.sh (about 15 minutes on 2 cores), or:
//   build/release/bin/path_error_vs_time OUT.csv
//   build/release/bin/path_error_vs_time --throughput   (part 1 alone)
#include "05-path-tracing/path_render.h"
#include "common/image_io.h"
#include "common/metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace rt::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Config {
  PathIntegrator integrator;
  SamplerKind sampler;
};

struct Point {
  int spp;
  double seconds, rmse;
};

struct Cornell {
  SceneDescription description = load_scene(std::string(RT_SOURCE_DIR) + "/assets/scenes/cornell-box.json");
  LightingScene scene{description};
  Camera camera{description.camera, 256, 256};
  Image reference = read_pfm(std::string(RT_SOURCE_DIR) + "/assets/references/cornell-box-256.pfm");
};

Image render(const Cornell& c, const Config& config, int spp, int threads, double& seconds) {
  RenderSettings settings;
  settings.width = settings.height = 256;
  settings.spp = spp;
  settings.seed = 1;
  PathOptions options;
  options.integrator = config.integrator;
  options.max_depth = c.description.render.max_depth;  // naive: the scene's depth, as stage5 renders it
  SampleGuard guard;
  const auto start = Clock::now();
  Image image = render_paths(c.scene, c.camera, settings, options, config.sampler, threads, guard);
  seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

// The time at which the log-log line through the measured points first crosses `target`.
double time_to_reach(const std::vector<Point>& points, double target) {
  for (size_t i = 1; i < points.size(); ++i)
    if (points[i].rmse <= target) {
      const Point& a = points[i - 1];
      const Point& b = points[i];
      if (a.rmse <= target) return a.seconds;
      const double f = std::log(a.rmse / target) / std::log(a.rmse / b.rmse);
      return std::exp(std::log(a.seconds) + f * std::log(b.seconds / a.seconds));
    }
  return NAN;
}

}  // namespace
}  // namespace rt::bench

int main(int argc, char** argv) {
  using namespace rt;
  using namespace rt::bench;
  const bool throughput_only = argc == 2 && std::string(argv[1]) == "--throughput";
  // Any other option (--help) is not taken for the name of the file to write.
  if (argc != 2 || (argv[1][0] == '-' && !throughput_only)) {
    std::fprintf(stderr, "usage: path_error_vs_time OUT.csv   (or --throughput: part 1 alone, about a minute)\n");
    return 2;
  }
  const Cornell c;

  // Best of three runs each, alternating 1 and 2 threads, so that a burst of other work on the
  // machine does not decide the scaling figure.
  std::printf("Throughput, 256 x 256 Cornell box, MIS, Sobol, 64 spp, best of 3 (%u hardware threads):\n",
              std::thread::hardware_concurrency());
  double best[3] = {0.0, 0.0, 0.0};
  for (int round = 0; round < 3; ++round)
    for (const int threads : {1, 2}) {
      double seconds = 0.0;
      render(c, {PathIntegrator::mis, SamplerKind::sobol}, 64, threads, seconds);
      best[threads] = std::max(best[threads], 256.0 * 256.0 * 64.0 / seconds);
    }
  std::printf("  1 thread : %.2f M paths/s\n  2 threads: %.2f M paths/s (x%.2f)\n", best[1] * 1e-6, best[2] * 1e-6,
              best[2] / best[1]);
  if (throughput_only) return 0;

  std::ofstream csv(argv[1]);
  csv << "integrator,sampler,spp,seconds,rmse\n";
  const Config configs[] = {{PathIntegrator::naive, SamplerKind::sobol},
                            {PathIntegrator::russian_roulette, SamplerKind::sobol},
                            {PathIntegrator::next_event_estimation, SamplerKind::sobol},
                            {PathIntegrator::mis, SamplerKind::sobol},
                            {PathIntegrator::mis, SamplerKind::independent}};
  std::printf("\nTime to reach an RMSE against the reference (all threads):\n");
  std::printf("  %-5s %-11s %9s %9s %9s   last render\n", "", "", "0.02", "0.01", "0.005");
  for (const Config& config : configs) {
    std::vector<Point> points;
    for (int spp = 1;; spp *= 2) {
      double seconds = 0.0;
      const double error = rmse(render(c, config, spp, 0, seconds), c.reference);
      points.push_back({spp, seconds, error});
      csv << integrator_name(config.integrator) << "," << sampler_name(config.sampler) << "," << spp << ","
          << seconds << "," << error << "\n";
      if (error < 0.004 || seconds > 60.0) break;
    }
    std::printf("  %-5s %-11s", integrator_name(config.integrator), sampler_name(config.sampler));
    for (const double target : {0.02, 0.01, 0.005}) {
      const double t = time_to_reach(points, target);
      if (std::isnan(t)) std::printf(" %9s", "-");
      else std::printf(" %8.2fs", t);
    }
    std::printf("   %d spp, %.1f s, RMSE %.4f\n", points.back().spp, points.back().seconds, points.back().rmse);
    std::fflush(stdout);
  }
  return csv.good() ? 0 : 1;
}
