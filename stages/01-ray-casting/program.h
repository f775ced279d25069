// Stage 1: the end of every stage program, shared by the later stages' programs: render with a
// progress bar (on a terminal), scale a depth view for PNG, write the image atomically, and print
// one line of figures.
#pragma once

#include "01-ray-casting/ray_caster.h"
#include "01-ray-casting/render.h"
#include "common/cli.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/image_io.h"
#include "common/progress.h"

#include <chrono>
#include <csignal>
#include <cstdio>

namespace rt {

// A depth image in scene units is mostly white in a PNG; scale it by the farthest hit.
void scale_depth_for_png(Image& image);

// `render(progress)` makes the image, advancing the progress bar by the samples it finishes.
template <class RenderFn>
void render_with_progress_and_write(const char* program, const CommonOptions& options,
                                    const RenderSettings& settings, DebugView view, RenderFn&& render) {
  const auto start = std::chrono::steady_clock::now();
  ProgressBar progress(std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                           std::uint64_t(settings.spp),
                       "samples");
  Image image = render(&progress);
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (view == DebugView::depth && image_format_for(options.out) == ImageFormat::png) scale_depth_for_png(image);
  write_image(options.out, image);
  const std::uint64_t asked = std::uint64_t(image.pixel_count()) * std::uint64_t(settings.spp);
  if (interrupt_requested()) {
    std::printf("%s: interrupted by %s: wrote %s with %s of %s samples (%.1f%%), each pixel the mean of "
                "the samples it finished, black where none\n",
                program, interrupt_signal() == SIGINT ? "Ctrl-C" : "SIGTERM", options.out.c_str(),
                format_si(double(progress.done())).c_str(), format_si(double(asked)).c_str(),
                100.0 * double(progress.done()) / double(asked));
    throw Interrupted{interrupt_signal()};
  }
  std::printf("%s: wrote %s (%dx%d, %d spp) in %.2f s, %ssamples/s\n", program, options.out.c_str(),
              settings.width, settings.height, settings.spp, seconds,
              format_si(double(asked) / seconds).c_str());
}

template <class SamplerType = Rng, class RadianceFn>
void render_and_write(const char* program, const CommonOptions& options, const RenderSettings& settings,
                      const PinholeCamera& camera, DebugView view, RadianceFn&& radiance) {
  render_with_progress_and_write(program, options, settings, view, [&](ProgressBar* progress) {
    return render_image<SamplerType>(camera, settings, options.threads, radiance, progress);
  });
}

}  // namespace rt
