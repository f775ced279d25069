// The command line every stage executable shares (docs/design.md): --scene --spp --out --width --height
// --threads --seed, plus the stage's own flags. Exit codes: 0 ok, 1 bad input, 2 bad usage; every
// failure is one line on stderr.
#pragma once

#include "common/image_io.h"
#include "common/memory_limit.h"
#include "common/scene.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rt {

// The first sample and the number of samples a --sample-range asks for.
struct SampleRangeFlag {
  int first = 0, count = 0;
};

struct CommonOptions {
  std::string scene;
  std::string out;  // .png or .pfm: the image; .json: a sample batch (common/sample_batch.h)
  std::optional<int> spp, width, height;
  std::optional<std::uint64_t> seed;
  std::optional<int> max_depth;  // registered by the stages that recurse (add_max_depth_flag)
  int threads = 0;  // 0 = all cores
  // Scale-out (docs/scale-out.md): "a:b" renders samples [a, b) of each pixel; "x0:x1,y0:y1" only
  // the pixels [x0, x1) x [y0, y1).
  std::optional<std::string> sample_range, crop;
  std::optional<std::string> filter;  // --filter: a pixel filter's name (kPixelFilterNames)
  ImageEncoding encoding;  // --exposure --tone --white --gamma --exr-half: how an image file encodes
  // The stage's own flags that shape the image, "--name=value ..." with defaults filled in, set by
  // run_stage_program: what a sample batch records so that only batches of one render merge.
  std::string image_flags;

  // The scene's render block with the command-line values put over it.
  // Throws UsageError for a sample range or crop window that is malformed or outside the image, or
  // for an output that is one of the scene's own files (the scene, a mesh); and InputError, with
  // the figures, for an image or a scene this process could not hold (common/memory_limit.h).
  RenderSettings settings_for(const SceneDescription& scene) const;
};

// "a:b" with 0 <= a < b <= kMaxSpp; "x0:x1,y0:y1" inside a width x height image with x0 < x1 and
// y0 < y1. Throw UsageError naming the flag and the problem.
SampleRangeFlag parse_sample_range(const std::string& text);
PixelRect parse_crop(const std::string& text, int width, int height);

// A CLI11 check for an integer flag: decimal digits only (CLI11 itself reads "010" as octal 8 and
// "0x10" as 16) with a value in [lo, hi], exact up to 2^64 - 1; the text is rewritten without its
// leading zeros before CLI11 converts it.
CLI::Validator decimal(std::uint64_t lo, std::uint64_t hi);

// A CLI11 check for a floating-point flag: a finite number in [lo, hi] (CLI::Range lets NaN
// through, since every comparison with NaN is false).
CLI::Validator finite_range(double lo, double hi);

// The flags of how an image file encodes (common/image_io.h, common/display_transform.h): --exposure,
// --tone, --white and --gamma for a PNG, --exr-half for an EXR. Every stage program and merge.
void add_image_encoding_flags(CLI::App& app, ImageEncoding& encoding);

// --max-depth, for the stage programs that follow rays recursively (stage 2 on).
void add_max_depth_flag(CLI::App& app, CommonOptions& options);

// Parses the command line into `options` (plus whatever `add_stage_flags` registered), then calls
// `run`. Maps --help to exit 0, usage errors to 2 and InputError to 1, each with one line on stderr
// that starts with the program name. The output path is checked before `run` is called, so no
// render is wasted on an unwritable path.
int run_stage_program(int argc, char** argv, const std::string& program, const std::string& title,
                      CommonOptions& options, const std::function<void(CLI::App&)>& add_stage_flags,
                      const std::function<void()>& run);

// The two halves of that, for any program of the project (the merge program too).
// Parses `app`: returns nothing when the run should go on, or the exit code after --help (0, help
// printed) or a usage error (2, one line "PROGRAM: error: ... (see --help)").
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program);
// Runs `body` and returns the exit code: 0; 2 for UsageError; 1 for InputError, out of memory or
// any other exception, each with one line "PROGRAM: error: ..." (control characters escaped);
// 128 + the signal for Interrupted, with its message if it has one. Out of memory names `subject`
// (the scene, say) and the limit this process runs under.
int run_reporting_errors(const std::string& program, const std::function<void()>& body,
                         const std::string& subject = "");

// The files an output writes: OUT itself, or for a sample batch NAME.json, NAME.sum.pfm and
// NAME.count.pfm (common/sample_batch.h).
std::vector<std::string> output_files(const std::string& out);
// Throws UsageError when an output file is one of `inputs`: writing it would destroy the input.
void require_outputs_spare_inputs(const std::string& out, const std::vector<std::string>& inputs);

}  // namespace rt
