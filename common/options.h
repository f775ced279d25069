// What every stage program is asked on its command line (docs/design.md), as plain values: the
// options the program shell renders with. Parsing them is common/cli.cpp's job, the one file of
// the stages' shell that sees CLI11, so that the libraries, programs and tests that only read
// options never compile it (CLI11 costs seconds in every file that includes it: docs/build.md).
#pragma once

#include "common/image_io.h"
#include "common/memory_limit.h"
#include "common/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rt {

// The first sample and the number of samples a --sample-range asks for.
struct SampleRangeFlag {
  int first = 0, count = 0;
};

// A file a render writes and the flag that names it, for messages.
struct NamedOutput {
  std::string flag, file;
};

struct CommonOptions {
  std::string scene;
  std::string out;  // .png or .pfm: the image; .json: a sample batch (common/sample_batch.h)
  std::optional<int> spp, width, height;
  std::optional<std::uint64_t> seed;
  std::optional<int> max_depth;  // registered by the stages that recurse (StageFlags::add_max_depth)
  int threads = 0;  // 0 = all cores
  // Scale-out (docs/scale-out.md): "a:b" renders samples [a, b) of each pixel; "x0:x1,y0:y1" only
  // the pixels [x0, x1) x [y0, y1).
  std::optional<std::string> sample_range, crop;
  std::optional<std::string> filter;  // --filter: a pixel filter's name (kPixelFilterNames)
  ImageEncoding encoding;  // --exposure --tone --white --gamma --exr-half: how an image file encodes
  // The stage's own flags that shape the image, "--name=value ..." with defaults filled in, set by
  // run_stage_program: what a sample batch records so that only batches of one render merge.
  std::string image_flags;
  // The outputs a stage's own flags name besides --out (stage 5's --sample-map), set by
  // run_stage_program: checked with --out's before anything renders.
  std::vector<NamedOutput> more_outputs;

  // The scene's render block with the command-line values put over it.
  // Throws UsageError for a sample range or crop window that is malformed or outside the image, or
  // for an output that is one of the files the scene reads (the scene, a mesh, a texture, the
  // environment map); and InputError, with
  // the figures, for an image or a scene this process could not hold (common/memory_limit.h).
  RenderSettings settings_for(const SceneDescription& scene) const;
};

// "a:b" with 0 <= a < b <= kMaxSpp; "x0:x1,y0:y1" inside a width x height image with x0 < x1 and
// y0 < y1. Throw UsageError naming the flag and the problem.
SampleRangeFlag parse_sample_range(const std::string& text);
PixelRect parse_crop(const std::string& text, int width, int height);

// The files an output writes: OUT itself, or for a sample batch NAME.json, NAME.sum.pfm and
// NAME.count.pfm (common/sample_batch.h).
std::vector<std::string> output_files(const std::string& out);
// The files a render writes, each named by its flag: --out's (output_files), then `more`.
std::vector<NamedOutput> outputs_of(const std::string& out, const std::vector<NamedOutput>& more = {});
// Throws InputError for an output that cannot be written (check_output_writable) and UsageError
// for two outputs that are one file.
void check_outputs(const std::vector<NamedOutput>& outputs);
// Throws UsageError when an output file is one of `inputs`: writing it would destroy the input.
void require_outputs_spare_inputs(const std::vector<NamedOutput>& outputs, const std::vector<std::string>& inputs);

}  // namespace rt
