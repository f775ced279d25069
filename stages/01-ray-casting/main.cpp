// stage1: renders a scene by ray casting with local shading (or one of its debug views).
#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "common/stage_program.h"

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  std::string debug_name = "none";

  return run_stage_program(
      argc, argv, "stage1", "Stage 1: ray casting with local shading under point lights", options,
      [&](StageFlags& flags) {
        flags.add_word("--debug", debug_name, {"none", "normal", "depth", "albedo"},
                       "Debug view instead of shading: none, normal, depth (scaled to [0, 1] in "
                       "PNG, raw distance in PFM), albedo");
      },
      [&] {
        const DebugView view = debug_view_from_name(debug_name);
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        const RayCastingScene scene(description);
        const Camera camera(description.camera, settings.width, settings.height);
        render_and_write("stage1", options, description, settings, camera, meaning_of(view),
                         [&](const Ray& ray, Rng&) { return cast_ray(scene, ray, view); });
      });
}
