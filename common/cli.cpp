#include "common/cli.h"

#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"
#include "common/interrupt.h"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <limits>

namespace rt {

RenderSettings CommonOptions::settings_for(const SceneDescription& scene) const {
  RenderSettings s = scene.render;
  if (spp) s.spp = *spp;
  if (width) s.width = *width;
  if (height) s.height = *height;
  if (seed) s.seed = *seed;
  if (max_depth) s.max_depth = *max_depth;
  check_image_fits(out, s.width, s.height, physical_memory_bytes());
  return s;
}

namespace {

std::string binary_size(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int unit = 0;
  for (; bytes >= 1024.0 && unit < 5; ++unit) bytes /= 1024.0;
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

}  // namespace

void check_image_fits(const std::string& out, int width, int height, std::uint64_t physical_bytes) {
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (pixels > std::uint64_t(std::numeric_limits<int>::max()))
    throw InputError(out + ": a " + size + " image has more than 2^31 - 1 pixels");
  const std::uint64_t needed = pixels * kBytesPerPixel;
  if (needed > physical_bytes)
    throw InputError(out + ": a " + size + " image needs " + binary_size(double(needed)) +
                     " of memory (the radiance and the encoded file), and this machine has " +
                     binary_size(double(physical_bytes)));
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return std::numeric_limits<std::uint64_t>::max();  // unknown: do not refuse
  return std::uint64_t(pages) * std::uint64_t(page_size);
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
  // CLI11 would wrap "-1" around to 2^64 - 1 for an unsigned option; a sign is refused instead.
  app.add_option("--seed", options.seed, "Random seed (default: the scene's)")
      ->check(CLI::Validator(
          [](const std::string& value) {
            return value.find('-') == std::string::npos ? std::string() : "a seed is a non-negative integer";
          },
          "UINT"));
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

  InterruptHandler interrupt_handler;
  try {
    image_format_for(options.out);
    check_output_writable(options.out);
    run();
    return kExitOk;
  } catch (const Interrupted& stop) {
    return 128 + stop.signal_number;
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
