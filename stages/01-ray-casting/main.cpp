// stage1: renders a scene by ray casting with local shading (or one of its debug views).
#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "common/cli.h"
#include "common/image_io.h"
#include "common/progress.h"

#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  std::string debug_name = "none";

  return run_stage_program(
      argc, argv, "stage1", "Stage 1: ray casting with local shading under point lights", options,
      [&](CLI::App& app) {
        app.add_option("--debug", debug_name,
                       "Debug view instead of shading: none, normal, depth (scaled to [0, 1] in "
                       "PNG, raw distance in PFM), albedo")
            ->check(CLI::IsMember({"none", "normal", "depth", "albedo"}));
      },
      [&] {
        const DebugView view = debug_view_from_name(debug_name);
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        const RayCastingScene scene(description);
        const PinholeCamera camera(description.camera, settings.width, settings.height);

        const auto start = std::chrono::steady_clock::now();
        ProgressBar progress(std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                                 std::uint64_t(settings.spp),
                             "samples");
        Image image = render_image(
            camera, settings, options.threads,
            [&](const Ray& ray, Rng&) { return cast_ray(scene, ray, view); }, &progress);
        progress.finish();
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        // A depth image in scene units is mostly white in a PNG; scale it by the farthest hit.
        if (view == DebugView::depth && image_format_for(options.out) == ImageFormat::png) {
          float farthest = 0.0f;
          for (const Color& c : image.pixels()) farthest = std::max(farthest, c.r);
          if (farthest > 0.0f)
            for (Color& c : image.pixels()) c /= farthest;
        }
        write_image(options.out, image);
        std::printf("stage1: wrote %s (%dx%d, %d spp) in %.2f s, %ssamples/s\n",
                    options.out.c_str(), settings.width, settings.height, settings.spp, seconds,
                    format_si(double(image.pixel_count()) * settings.spp / seconds).c_str());
      });
}
