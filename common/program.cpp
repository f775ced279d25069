#include "common/program.h"

#include "common/error.h"
#include "common/image_io.h"
#include "common/interrupt.h"
#include "common/sample_batch.h"

#include <cmath>
#include <csignal>
#include <cstdio>

namespace rt {

void scale_depth_for_png(Image& image) {
  float farthest = 0.0f;
  for (const Color& c : image.pixels()) farthest = std::max(farthest, c.r);
  if (farthest > 0.0f)
    for (Color& c : image.pixels()) c /= farthest;
}

namespace {

// "256x256, 16 spp", or for part of a render "pixels 0:64,0:64 of 256x256, samples 16:32".
std::string describe_part(const RenderSettings& s) {
  const PixelRect window = s.window();
  const bool whole_image = window == PixelRect{0, 0, s.width, s.height};
  const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
  std::string text = whole_image ? size : "pixels " + format_rect(window) + " of " + size;
  if (s.first_sample == 0) return text + ", " + std::to_string(s.spp) + " spp";
  return text + ", samples " + format_range({s.first_sample, s.first_sample + s.spp});
}

SampleBatch batch_of(const char* program, const CommonOptions& options, const std::string& scene,
                     const SceneDescription& description, const RenderSettings& s, const SampleSums& sums) {
  SampleBatch batch;
  batch.file = options.out;
  batch.identity = {program,
                    scene,
                    scene_fingerprint(scene, description),
                    options.image_flags + " --max-depth=" + std::to_string(s.max_depth) +
                        " --filter=" + pixel_filter_name(s.filter),
                    s.width,
                    s.height,
                    s.seed};
  batch.window = s.window();
  batch.pieces = {{s.window(), {s.first_sample, s.first_sample + s.spp}}};
  batch.interrupted = interrupt_requested();
  batch.sums = sums;
  return batch;
}

// Samples whose radiance came out NaN or infinite (a bug, or a scene at the edge of float range)
// would poison every later use of the image: they are counted and written black, with a warning,
// so that no output file ever holds a non-finite value.
void blacken_non_finite(const char* program, SampleSums& sums) {
  std::uint64_t bad = 0;
  for (Color& c : sums.sums().pixels())
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) {
      c = Color(0.0f);
      ++bad;
    }
  if (bad > 0)
    std::fprintf(stderr, "%s: warning: %llu pixels had a radiance that is not finite and are written black\n", program,
                 static_cast<unsigned long long>(bad));
}

}  // namespace

void write_render(const char* program, const CommonOptions& options, const std::string& scene,
                  const SceneDescription& description, const RenderSettings& settings, PixelMeaning meaning,
                  const SampleSums& rendered, double seconds) {
  const std::uint64_t asked = std::uint64_t(settings.window().area()) * std::uint64_t(settings.spp);
  const std::uint64_t done = rendered.total_count();
  const char* signal_name = interrupt_signal() == SIGINT ? "Ctrl-C" : interrupt_signal() == SIGHUP ? "SIGHUP" : "SIGTERM";
  // A stop before the first sample (during loading, say) leaves an existing output as it was:
  // a black image would replace a good one with nothing.
  if (interrupt_requested() && done == 0)
    throw Interrupted{interrupt_signal(), std::string("interrupted by ") + signal_name +
                                              " before any sample finished: nothing written"};
  SampleSums sums = rendered;
  blacken_non_finite(program, sums);
  const bool batch = is_batch_path(options.out);
  if (batch) {
    write_sample_batch(batch_of(program, options, scene, description, settings, sums));
  } else {
    Image image = sums.mean();
    if (meaning == PixelMeaning::depth && image_format_for(options.out) == ImageFormat::png) scale_depth_for_png(image);
    write_output_image(program, options.out, image, options.encoding);
  }
  if (interrupt_requested()) {
    std::printf("%s: interrupted by %s: wrote %s with %s of %s samples (%.1f%%), %s\n", program, signal_name,
                printable(options.out).c_str(), format_si(double(done)).c_str(), format_si(double(asked)).c_str(),
                100.0 * double(done) / double(asked),
                batch ? "marked interrupted (merge --partial takes it)"
                      : "each pixel the mean of the samples it finished, black where none");
    throw Interrupted{interrupt_signal(), ""};
  }
  std::printf("%s: wrote %s%s (%s) in %.2f s, %ssamples/s\n", program, batch ? "sample batch " : "",
              printable(options.out).c_str(), describe_part(settings).c_str(), seconds,
              format_si(double(done) / seconds).c_str());
}

}  // namespace rt
