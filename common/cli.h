// The command line every stage executable shares (DESIGN.md): --scene --spp --out --width --height
// --threads --seed, plus the stage's own flags. Exit codes: 0 ok, 1 bad input, 2 bad usage; every
// failure is one line on stderr.
#pragma once

#include "common/scene.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace rt {

struct CommonOptions {
  std::string scene;
  std::string out;
  std::optional<int> spp, width, height;
  std::optional<std::uint64_t> seed;
  std::optional<int> max_depth;  // registered by the stages that recurse (add_max_depth_flag)
  int threads = 0;  // 0 = all cores

  // The scene's render block with the command-line values put over it.
  // Throws InputError (naming the output file, with the figures) for an image this machine could
  // not hold: see check_image_fits.
  RenderSettings settings_for(const SceneDescription& scene) const;
};

// Refuses, before anything is allocated, an image of more than 2^31 - 1 pixels or one whose
// memory (kBytesPerPixel: the radiance, 12 bytes, and the encoded file, up to 12 more) exceeds
// `physical_bytes`, the machine's memory. Throws InputError "OUT: a WxH image needs ..., this
// machine has ...".
inline constexpr std::uint64_t kBytesPerPixel = 24;
void check_image_fits(const std::string& out, int width, int height, std::uint64_t physical_bytes);
// The machine's physical memory in bytes (sysconf).
std::uint64_t physical_memory_bytes();

// --max-depth, for the stage programs that follow rays recursively (stage 2 on).
void add_max_depth_flag(CLI::App& app, CommonOptions& options);

// Parses the command line into `options` (plus whatever `add_stage_flags` registered), then calls
// `run`. Maps --help to exit 0, usage errors to 2 and InputError to 1, each with one line on stderr
// that starts with the program name. The output path is checked before `run` is called, so no
// render is wasted on an unwritable path.
int run_stage_program(int argc, char** argv, const std::string& program, const std::string& title,
                      CommonOptions& options, const std::function<void(CLI::App&)>& add_stage_flags,
                      const std::function<void()>& run);

}  // namespace rt
