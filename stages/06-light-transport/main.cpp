// stage6: renders a scene by path tracing, light tracing, bidirectional path tracing or stochastic
// progressive photon mapping.
#include "01-ray-casting/render.h"
#include "06-light-transport/transport_render.h"
#include "common/error.h"
#include "common/sample_batch.h"
#include "common/stage_program.h"

#include <utility>
#include <vector>

namespace {

// "s,t" with s >= 0, t >= 1, s + t >= 2 (a strategy BDPT has).
rt::StrategyFilter parse_strategy(const std::string& text) {
  int s = -1, t = -1;
  char comma = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> s >> comma >> t) || comma != ',' || (in >> extra) || s < 0 || t < 1 || s + t < 2 || s + t > 64)
    throw rt::UsageError("--strategy: expected s,t with s >= 0, t >= 1 and 2 <= s + t <= 64 (e.g. 2,1), got '" +
                         text + "'");
  return rt::StrategyFilter{s, t};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rt;
  CommonOptions options;
  TransportOptions transport;
  std::string strategy;

  return run_stage_program(
      argc, argv, "stage6", "Stage 6: light transport beyond path tracing", options,
      [&](StageFlags& flags) {
        flags.add_max_depth(options,
                            "sppm: the mirror and glass bounces to a pixel's visible point (pt, lt and bdpt end "
                            "paths by Russian roulette and refuse it)");
        std::vector<std::pair<std::string, TransportMethod>> methods;
        for (const TransportMethod m : kTransportMethods) methods.emplace_back(method_name(m), m);
        flags.add_choice("--method", transport.method, methods,
                         "pt (stage 5's path tracer), lt (light tracing), bdpt (bidirectional path tracing, the "
                         "default) or sppm (stochastic progressive photon mapping; --spp is its number of passes)");
        flags.add("--strategy", strategy,
                  "bdpt: render the one strategy s,t alone, unweighted (s light vertices, t camera vertices)");
        flags.add("--photons", transport.sppm.photons_per_pass, "sppm: photons per pass (default 100000)",
                  decimal_in(1, 100000000));
        flags.add("--radius", transport.sppm.initial_radius,
                  "sppm: the initial gather radius in scene units (default: one pixel footprint at each "
                  "pixel's first visible point)",
                  finite_in(1e-30, 1e30));
        flags.add("--alpha", transport.sppm.alpha,
                  "sppm: the share of new photons each pass keeps, in (0, 1] (default 2/3)", finite_in(1e-6, 1.0));
        flags.add("--roulette-start", transport.bdpt.walk.roulette_start,
                  "Bounces before Russian roulette may end a subpath (default 4)", decimal_in(0, 1000));
      },
      [&] {
        if (options.max_depth && transport.method != TransportMethod::sppm)
          throw UsageError(std::string("--max-depth: --method ") + method_name(transport.method) +
                           " ends paths by Russian roulette, with no depth to limit; the depth is sppm's, through "
                           "mirrors and glass to a pixel's visible point");
        const bool splits = transport.method != TransportMethod::pt;
        if (splits && (options.sample_range || options.crop || is_batch_path(options.out)))
          throw UsageError(std::string("--method ") + method_name(transport.method) +
                           ": light paths land anywhere on the film and photon radii shrink with every pass, so "
                           "the image cannot be rendered in batches or windows: render it whole (--method pt can)");
        if (!strategy.empty()) {
          if (transport.method != TransportMethod::bdpt) throw UsageError("--strategy is for --method bdpt");
          transport.bdpt.only = parse_strategy(strategy);
        }
        const SceneDescription description = load_scene(options.scene);
        const RenderSettings settings = options.settings_for(description);
        check_transport_fits(description, settings, transport, memory_limit());
        if (splits && settings.filter != PixelFilterType::box)
          throw UsageError("--filter: lt, bdpt and sppm use the box filter (a splat lands in one pixel; a visible "
                           "point stands for one pixel); other filters, from --filter or the scene, need --method pt");
        transport.path.max_depth = settings.max_depth;
        transport.path.roulette_start = transport.sppm.walk.roulette_start = transport.bdpt.walk.roulette_start;
        transport.sppm.max_depth = settings.max_depth;
        const LightingScene scene(description);
        const Camera camera(description.camera, settings.width, settings.height);
        check_renderable(description, scene, camera, transport.method);
        SampleGuard guard;
        render_with_progress_and_write("stage6", options, description, settings, PixelMeaning::radiance,
                                       [&](ProgressBar* progress) {
                                         return render_transport(scene, camera, settings, transport, options.threads,
                                                                 guard, progress);
                                       });
        if (guard.dropped() > 0)
          std::printf("stage6: %llu samples had NaN, infinite or negative radiance and were counted as black\n",
                      static_cast<unsigned long long>(guard.dropped()));
      });
}
