// The end of every stage program: render with a progress bar (on a terminal), then write the image
// (a depth image scaled for PNG) or, for an output ending in .json, the sample batch
// (common/sample_batch.h), atomically, and print one line of figures.
#pragma once

#include "common/options.h"
#include "common/progress.h"
#include "common/sample_sums.h"
#include "common/scene.h"

#include <chrono>

namespace rt {

// What the pixels hold: radiance, or a distance in scene units (a depth view), which a PNG shows
// scaled by the farthest hit, since most distances would be white.
enum class PixelMeaning { radiance, depth };

void scale_depth_for_png(Image& image);

// Writes what a render made to options.out and reports it (or, after Ctrl-C, SIGTERM or SIGHUP, how
// much of it there is, then throws Interrupted). `scene` and `description` identify a sample batch.
void write_render(const char* program, const CommonOptions& options, const std::string& scene,
                  const SceneDescription& description, const RenderSettings& settings, PixelMeaning meaning,
                  const SampleSums& sums, double seconds);

// `render(progress)` returns the sample sums of settings.window(), advancing the progress bar by
// the samples it finishes.
template <class RenderFn>
void render_with_progress_and_write(const char* program, const CommonOptions& options,
                                    const SceneDescription& description, const RenderSettings& settings,
                                    PixelMeaning meaning, RenderFn&& render) {
  const auto start = std::chrono::steady_clock::now();
  ProgressBar progress(std::uint64_t(settings.window().area()) * std::uint64_t(settings.spp), "samples");
  const SampleSums sums = render(&progress);
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_render(program, options, options.scene, description, settings, meaning, sums, seconds);
}

}  // namespace rt
