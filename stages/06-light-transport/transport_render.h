// Stage 6: a whole image by each of the stage's methods, shared by the program, the tests and the
// benchmarks, so all three render the same way.
//  - pt:   stage 5's path tracer (MIS, Sobol), the baseline;
//  - lt:   light tracing (light_tracer.h), every contribution splatted;
//  - bdpt: bidirectional path tracing (bdpt.h), strategies with t >= 2 into the sample's own pixel,
//          t = 1 splatted;
//  - sppm: stochastic progressive photon mapping (sppm.h), spp passes.
// Splats land on any pixel, from any thread; each tile keeps its own list per pass and the lists
// are added in tile order after the pass, so the image is the same bit for bit for any thread count.
#pragma once

#include "05-path-tracing/path_render.h"
#include "06-light-transport/bdpt.h"
#include "06-light-transport/sppm.h"

namespace rt {

enum class TransportMethod { pt, lt, bdpt, sppm };
inline constexpr TransportMethod kTransportMethods[] = {TransportMethod::pt, TransportMethod::lt,
                                                        TransportMethod::bdpt, TransportMethod::sppm};
const char* method_name(TransportMethod method);  // pt, lt, bdpt, sppm

struct TransportOptions {
  TransportMethod method = TransportMethod::bdpt;
  PathOptions path;  // pt
  BdptOptions bdpt;  // lt uses its walk settings
  SppmOptions sppm;
};

// Throws InputError, one line naming the scene file, for what `method` cannot render: lt, bdpt and
// sppm start paths on area emitters, so a scene needs one and may have no point light (no area to
// start on) or environment (stage 5 renders both: --method pt); lt and bdpt connect to a pinhole,
// so the camera may have no aperture.
void check_renderable(const SceneDescription& description, const LightingScene& scene, const Camera& camera,
                      TransportMethod method);
// The same rule for any method that starts paths on lights (`what`, as the user asked for it, e.g.
// "--method bdpt"), naming `path_tracer` as what renders the scene instead, and for a method that
// connects to a pinhole, `lens_alternative` as what renders a camera with an aperture (empty: the
// method takes a lens).
void check_light_paths_renderable(const SceneDescription& description, const LightingScene& scene, const Camera& camera,
                                  const std::string& what, const std::string& path_tracer,
                                  const std::string& lens_alternative);

// Throws InputError, before the scene is built, for a render `options.method` could not hold within
// `limit`: every stage's kBytesPerPixel (common/memory_limit.h) and what the method adds, each
// figure measured as peak resident memory (/usr/bin/time on the Cornell box, two sizes apart):
// lt and bdpt 64 bytes a pixel (the splats' double-precision film and the tiles' splat lists),
// sppm 192 a pixel (visible points, photon statistics, two light sums) and 192 a photon of a pass
// (the chunks the threads fill, the grid's sorted copy and its table).
inline constexpr std::uint64_t kSplatBytesPerPixel = 64, kSppmBytesPerPixel = 192, kSppmBytesPerPhoton = 192;
void check_transport_fits(const SceneDescription& description, const RenderSettings& settings,
                          const TransportOptions& options, const MemoryLimit& limit);

// Per pixel of settings.window() (the whole image for lt, bdpt and sppm) the sum of its samples
// and their number. For lt and bdpt a light-tracing splat counts (pixels / light paths) times, one
// light path having been traced per camera sample (camera_importance.h); they take the box filter
// only (std::invalid_argument otherwise), since a splat lands in one pixel. NaN, infinite or
// negative samples and splats are counted by `guard` and enter as black.
SampleSums render_transport(const LightingScene& scene, const Camera& camera, const RenderSettings& settings,
                            const TransportOptions& options, int threads, SampleGuard& guard,
                            ProgressBar* progress = nullptr);

}  // namespace rt
