#include "common/cli.h"

#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"

#include <cstdio>
#include <exception>

namespace rt {

RenderSettings CommonOptions::settings_for(const SceneDescription& scene) const {
  RenderSettings s = scene.render;
  if (spp) s.spp = *spp;
  if (width) s.width = *width;
  if (height) s.height = *height;
  if (seed) s.seed = *seed;
  if (max_depth) s.max_depth = *max_depth;
  return s;
}

void add_max_depth_flag(CLI::App& app, CommonOptions& options) {
  app.add_option("--max-depth", options.max_depth,
                 "Recursion depth limit: bounces followed before a path stops (default: the scene's)")
      ->check(CLI::Range(0, 1000));
}

int run_stage_program(int argc, char** argv, const std::string& program, const std::string& title,
                      CommonOptions& options, const std::function<void(CLI::App&)>& add_stage_flags,
                      const std::function<void()>& run) {
  CLI::App app(title, program);
  app.add_option("--scene", options.scene, "Scene file (JSON, see docs/scene-format.md)")
      ->required();
  app.add_option("--out", options.out, "Output image; the ending picks the format: .png or .pfm")
      ->required();
  app.add_option("--spp", options.spp, "Samples per pixel (default: the scene's)")
      ->check(CLI::Range(1, kMaxSpp));
  app.add_option("--width", options.width, "Image width in pixels (default: the scene's)")
      ->check(CLI::Range(1, kMaxImageSide));
  app.add_option("--height", options.height, "Image height in pixels (default: the scene's)")
      ->check(CLI::Range(1, kMaxImageSide));
  app.add_option("--threads", options.threads, "Worker threads, 0 = all cores")
      ->check(CLI::Range(0, 1024));
  app.add_option("--seed", options.seed, "Random seed (default: the scene's)");
  add_stage_flags(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: error: %s (see --help)\n", program.c_str(), e.what());
    return kExitBadUsage;
  }

  try {
    image_format_for(options.out);
    check_output_writable(options.out);
    run();
    return kExitOk;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitBadUsage;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: error: out of memory\n", program.c_str());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitBadInput;
  }
}

}  // namespace rt
