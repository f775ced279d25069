// stage5: renders a scene by Monte Carlo path tracing with one of the lecture's integrators.
#include "01-ray-casting/render.h"
#include "04-radiometry/light_sampling_flags.h"
#include "05-path-tracing/path_render.h"

#include <map>

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  PathOptions path;
  LightingOptions lighting;
  SamplerKind sampler = SamplerKind::sobol;

  return run_stage_program(
      argc, argv, "stage5", "Stage 5: Monte Carlo path tracing", options,
      [&](CLI::App& app) {
        add_max_depth_flag(app, options);
        std::map<std::string, PathIntegrator> integrators;
        for (const PathIntegrator i : kPathIntegrators) integrators[integrator_name(i)] = i;
        app.add_option("--integrator", path.integrator,
                       "naive (BRDF sampling, fixed depth), rr (Russian roulette), nee (light sampling), "
                       "or mis (the default)")
            ->transform(CLI::CheckedTransformer(integrators));
        app.add_option("--roulette-start", path.roulette_start,
                       "Bounces before Russian roulette may end a path (rr, nee, mis; default 4)")
            ->transform(decimal(0, 1000));
        app.add_option("--sampler", sampler, "independent (random numbers) or sobol (scrambled Sobol, the default)")
            ->transform(CLI::CheckedTransformer(std::map<std::string, SamplerKind>{
                {sampler_name(SamplerKind::independent), SamplerKind::independent},
                {sampler_name(SamplerKind::sobol), SamplerKind::sobol}}));
        add_rectangle_sampling_flag(app, lighting);
      },
      [&] {
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        path.max_depth = settings.max_depth;
        const LightingScene scene(description, lighting);
        const Camera camera(description.camera, settings.width, settings.height);
        SampleGuard guard;
        render_with_progress_and_write("stage5", options, description, settings, PixelMeaning::radiance,
                                       [&](ProgressBar* progress) {
                                         return render_path_samples(scene, camera, settings, path, sampler,
                                                                    options.threads, guard, progress);
                                       });
        if (guard.dropped() > 0)
          std::printf("stage5: %llu samples had NaN, infinite or negative radiance and were counted as black\n",
                      static_cast<unsigned long long>(guard.dropped()));
      });
}
