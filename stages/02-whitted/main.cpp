// stage2: renders a scene by Whitted-style recursive ray tracing (or one of its debug views).
#include "01-ray-casting/render.h"
#include "02-whitted/whitted.h"
#include "common/stage_program.h"


int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  std::string debug_name = "none";
  WhittedOptions whitted;
  TriangleMethod triangle_method = TriangleMethod::watertight;

  return run_stage_program(
      argc, argv, "stage2", "Stage 2: Whitted-style ray tracing: mirrors, glass, shadows, meshes", options,
      [&](StageFlags& flags) {
        flags.add_max_depth(options, "the mirror and glass bounces a ray is followed through");
        flags.add_word("--debug", debug_name, {"none", "normal", "depth", "albedo"},
                       "Debug view instead of shading: none, normal (shading normal), depth, albedo");
        flags.add_choice("--fresnel", whitted.fresnel, {{"exact", FresnelModel::exact}, {"schlick", FresnelModel::schlick}},
                         "Fresnel reflectance of glass: exact or schlick");
        flags.add_choice("--offset", whitted.offset.method,
                         {{"error-bound", OffsetMethod::error_bound},
                          {"integer-ulp", OffsetMethod::integer_ulp},
                          {"fixed", OffsetMethod::fixed}},
                         "Where secondary rays start: error-bound (default), integer-ulp, or fixed "
                         "(--epsilon along the normal)");
        flags.add("--epsilon", whitted.offset.epsilon, "Offset distance for --offset fixed", finite_in(0.0, 3.0e38));
        flags.add_choice("--triangle", triangle_method,
                         {{"watertight", TriangleMethod::watertight},
                          {"watertight-lanes", TriangleMethod::watertight_lanes},
                          {"moller-trumbore", TriangleMethod::moller_trumbore}},
                         "Ray-triangle test: watertight (default), watertight-lanes (the same answers, the "
                         "corners in SIMD lanes) or moller-trumbore");
      },
      [&] {
        const DebugView view = debug_view_from_name(debug_name);
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        whitted.max_depth = settings.max_depth;
        const WhittedScene scene(description, triangle_method);
        const Camera camera(description.camera, settings.width, settings.height);
        render_and_write("stage2", options, description, settings, camera, meaning_of(view), [&](const Ray& ray, Rng&) {
          return view == DebugView::none ? whitted_radiance(scene, ray, whitted) : whitted_debug(scene, ray, view);
        });
      });
}
