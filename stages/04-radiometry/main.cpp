// stage4: renders a scene's direct lighting by Monte Carlo integration, with one of four estimators.
#include "01-ray-casting/render.h"
#include "04-radiometry/direct_lighting.h"
#include "04-radiometry/light_sampling_flags.h"
#include "common/stage_program.h"


int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  DirectOptions direct;
  LightingOptions lighting;

  return run_stage_program(
      argc, argv, "stage4", "Stage 4: direct lighting by Monte Carlo integration of the reflection equation", options,
      [&](StageFlags& flags) {
        flags.add_max_depth(options, "the mirror and glass bounces followed to a surface that is lit");
        flags.add_choice("--estimator", direct.estimator,
                         {{"uniform", DirectEstimator::uniform_hemisphere},
                          {"cosine", DirectEstimator::cosine_hemisphere},
                          {"brdf", DirectEstimator::brdf},
                          {"light", DirectEstimator::light}},
                         "How directions are chosen: uniform (hemisphere), cosine (hemisphere), brdf, or light "
                         "(emitter sampling, the default)");
        flags.add_choice("--sphere-sampling", lighting.sphere_sampling,
                         {{"cone", SphereSampling::cone}, {"area", SphereSampling::area}},
                         "How sphere lights are sampled: cone (the directions they subtend, default) or area");
        add_rectangle_sampling_flag(flags, lighting);
        add_environment_sampling_flag(flags, lighting);
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
