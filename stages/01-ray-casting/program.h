// Stage 1: the end of every stage program, shared by the later stages' programs: render with a
// progress bar (on a terminal), then write the image (a depth view scaled for PNG) or, for an
// output ending in .json, the sample batch (common/sample_batch.h), atomically, and print one line
// of figures.
#pragma once

#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "common/cli.h"
#include "common/progress.h"
#include "common/sample_sums.h"
#include "common/scene.h"

#include <chrono>

namespace rt {

// A depth image in scene units is mostly white in a PNG; scale it by the farthest hit.
void scale_depth_for_png(Image& image);

// Writes what a render made to options.out and reports it (or, after Ctrl-C or SIGTERM, how much
// of it there is, then throws Interrupted). `scene` and `description` identify a sample batch.
void write_render(const char* program, const CommonOptions& options, const std::string& scene,
                  const SceneDescription& description, const RenderSettings& settings, DebugView view,
                  const SampleSums& sums, double seconds);

// `render(progress)` returns the sample sums of settings.window(), advancing the progress bar by
// the samples it finishes.
template <class RenderFn>
void render_with_progress_and_write(const char* program, const CommonOptions& options,
                                    const SceneDescription& description, const RenderSettings& settings,
                                    DebugView view, RenderFn&& render) {
  const auto start = std::chrono::steady_clock::now();
  ProgressBar progress(std::uint64_t(settings.window().area()) * std::uint64_t(settings.spp), "samples");
  const SampleSums sums = render(&progress);
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_render(program, options, options.scene, description, settings, view, sums, seconds);
}

template <class SamplerType = Rng, class RadianceFn>
void render_and_write(const char* program, const CommonOptions& options, const SceneDescription& description,
                      const RenderSettings& settings, const PinholeCamera& camera, DebugView view,
                      RadianceFn&& radiance) {
  render_with_progress_and_write(program, options, description, settings, view, [&](ProgressBar* progress) {
    return render_samples<SamplerType>(camera, settings, options.threads, radiance, progress);
  });
}

}  // namespace rt
