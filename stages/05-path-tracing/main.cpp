// stage5: renders a scene by Monte Carlo path tracing with one of the lecture's integrators.
#include "01-ray-casting/render.h"
#include "04-radiometry/light_sampling_flags.h"
#include "05-path-tracing/path_render.h"
#include "common/error.h"
#include "common/heat_map.h"
#include "common/image_io.h"
#include "common/sample_batch.h"
#include "common/stage_program.h"

#include <utility>
#include <vector>

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  PathOptions path;
  LightingOptions lighting;
  SamplerKind sampler = SamplerKind::sobol;
  std::optional<float> adaptive_tolerance;
  AdaptiveSettings adaptive;
  std::string sample_map;

  return run_stage_program(
      argc, argv, "stage5", "Stage 5: Monte Carlo path tracing", options,
      [&](StageFlags& flags) {
        flags.add_max_depth(options,
                            "the bounces of --integrator naive (rr, nee and mis end paths by Russian roulette "
                            "and refuse it)");
        std::vector<std::pair<std::string, PathIntegrator>> integrators;
        for (const PathIntegrator i : kPathIntegrators) integrators.emplace_back(integrator_name(i), i);
        flags.add_choice("--integrator", path.integrator, integrators,
                         "naive (BRDF sampling, fixed depth), rr (Russian roulette), nee (light sampling), "
                         "or mis (the default)");
        flags.add("--roulette-start", path.roulette_start,
                  "Bounces before Russian roulette may end a path (rr, nee, mis; default 4)", decimal_in(0, 1000));
        flags.add_choice("--sampler", sampler, sampler_words(),
                         "independent (random numbers) or sobol (scrambled Sobol, the default)");
        add_rectangle_sampling_flag(flags, lighting);
        add_environment_sampling_flag(flags, lighting);
        flags.add("--adaptive", adaptive_tolerance,
                  "Adaptive sampling: each pixel stops once the 95% confidence interval of its mean is within "
                  "this fraction of it (e.g. 0.05), after at least --adaptive-min-spp and at most --spp paths",
                  finite_in(1e-6, 1.0));
        flags.add("--adaptive-min-spp", adaptive.min_spp, "Paths per pixel before the first test (default 16)",
                  decimal_in(2, kMaxSpp));
        flags.add_output("--sample-map", sample_map,
                  "Also write a PNG heat map of the paths each pixel took (black: none, pale yellow: --spp)");
      },
      [&] {
        if (options.max_depth && path.integrator != PathIntegrator::naive)
          throw UsageError(std::string("--max-depth: --integrator ") + integrator_name(path.integrator) +
                           " ends paths by Russian roulette, with no depth to limit; the depth is naive's");
        if (adaptive_tolerance && (options.sample_range || is_batch_path(options.out)))
          throw UsageError("--adaptive: each pixel stops where its own samples say, so batches of one render "
                           "cannot be rendered apart and merged; render the image in one run");
        if (!sample_map.empty() && image_format_for(sample_map) != ImageFormat::png)
          throw UsageError("--sample-map: the heat map is a picture: give a .png file");
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        path.max_depth = settings.max_depth;
        if (adaptive_tolerance) adaptive.tolerance = *adaptive_tolerance;
        const LightingScene scene(description, lighting);
        const Camera camera(description.camera, settings.width, settings.height);
        SampleGuard guard;
        render_with_progress_and_write("stage5", options, description, settings, PixelMeaning::radiance,
                                       [&](ProgressBar* progress) {
                                         SampleSums sums = render_path_samples(
                                             scene, camera, settings, path, sampler, options.threads, guard,
                                             progress, adaptive_tolerance ? &adaptive : nullptr);
                                         if (adaptive_tolerance)
                                           std::printf("stage5: adaptive: %.1f paths per pixel on average, of %d\n",
                                                       double(sums.total_count()) / double(settings.window().area()),
                                                       settings.spp);
                                         if (!sample_map.empty())
                                           write_image(sample_map, heat_map(sums.counts(), sums.width(), sums.height(),
                                                                            std::uint32_t(settings.spp)));
                                         return sums;
                                       });
        if (guard.dropped() > 0)
          std::printf("stage5: %llu samples had NaN, infinite or negative radiance and were counted as black\n",
                      static_cast<unsigned long long>(guard.dropped()));
      });
}
