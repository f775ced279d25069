// stage4: renders a scene's direct lighting by Monte Carlo integration, with one of four estimators.
#include "01-ray-casting/render.h"
#include "04-radiometry/direct_lighting.h"
#include "04-radiometry/light_sampling_flags.h"
#include "common/cli.h"

#include <map>

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  DirectOptions direct;
  LightingOptions lighting;

  return run_stage_program(
      argc, argv, "stage4", "Stage 4: direct lighting by Monte Carlo integration of the reflection equation", options,
      [&](CLI::App& app) {
        add_max_depth_flag(app, options);
        app.add_option("--estimator", direct.estimator,
                       "How directions are chosen: uniform (hemisphere), cosine (hemisphere), brdf, or light "
                       "(emitter sampling, the default)")
            ->transform(CLI::CheckedTransformer(std::map<std::string, DirectEstimator>{
                {"uniform", DirectEstimator::uniform_hemisphere},
                {"cosine", DirectEstimator::cosine_hemisphere},
                {"brdf", DirectEstimator::brdf},
                {"light", DirectEstimator::light}}));
        app.add_option("--sphere-sampling", lighting.sphere_sampling,
                       "How sphere lights are sampled: cone (the directions they subtend, default) or area")
            ->transform(CLI::CheckedTransformer(std::map<std::string, SphereSampling>{
                {"cone", SphereSampling::cone}, {"area", SphereSampling::area}}));
        add_rectangle_sampling_flag(app, lighting);
        add_environment_sampling_flag(app, lighting);
      },
      [&] {
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        direct.max_depth = settings.max_depth;
        const LightingScene scene(description, lighting);
        std::printf("stage4: %zu area emitter%s, %zu point light%s%s\n", scene.emitters().size(),
                    scene.emitters().size() == 1 ? "" : "s", scene.lights().size(), scene.lights().size() == 1 ? "" : "s",
                    scene.environment() ? ", an environment" : "");
        const Camera camera(description.camera, settings.width, settings.height);
        render_and_write("stage4", options, description, settings, camera, PixelMeaning::radiance,
                         [&](const Ray& ray, Sampler& rng) { return direct_radiance(scene, ray, direct, rng); });
      });
}
