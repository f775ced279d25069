// merge: adds sample batches (common/sample_batch.h), written by any stage program with
// --out NAME.json, into one render, and says how far it has got (docs/scale-out.md).
//
//   merge --out OUT [--spp N] [--partial] [--reference REF.pfm] [--exposure S --tone T ...] BATCH...
//
// A BATCH is a description NAME.json or a folder (every *.json in it). OUT ending in .png, .pfm or
// .exr gets the image (a PNG through the display transform flags, as in the stage programs);
// ending in .json, the merged batch, to be merged again later (one merge per machine, then one of
// those). Exit codes as the stage programs: 1 for batches that do not add up
// (each refusal one line naming the files), 2 for bad usage.
#include "common/batch_merge.h"
#include "common/cli.h"
#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"
#include "common/metrics.h"
#include "common/sample_batch.h"
#include "common/scene.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace rt;

namespace {

std::vector<SampleBatch> read_batches(const std::vector<std::string>& inputs) {
  std::vector<SampleBatch> batches;
  for (const std::string& input : inputs) {
    if (!fs::is_directory(input)) {
      if (!is_batch_path(input))
        throw UsageError(input + ": not a batch description: give the NAME.json a stage program wrote, or a folder");
      batches.push_back(read_sample_batch(input));
      continue;
    }
    std::vector<fs::path> found;
    for (const fs::directory_entry& entry : fs::directory_iterator(input))
      if (entry.is_regular_file() && is_batch_path(entry.path())) found.push_back(entry.path());
    if (found.empty()) throw InputError(input + ": no sample batches (*.json) in this folder");
    std::sort(found.begin(), found.end());
    for (const fs::path& path : found) batches.push_back(read_sample_batch(path));
  }
  return batches;
}

std::string spp_reached(const MergeResult& r) {
  char text[160];
  if (r.min_spp == r.max_spp)
    std::snprintf(text, sizeof text, "%u of %d spp", r.max_spp, r.target_spp);
  else
    std::snprintf(text, sizeof text, "%u to %u spp per pixel, mean %.1f, of %d", r.min_spp, r.max_spp, r.mean_spp,
                  r.target_spp);
  return text;
}

void run(const std::string& out, const std::optional<int>& spp, bool partial, const std::optional<std::string>& reference,
         const std::vector<std::string>& inputs, const ImageEncoding& encoding) {
  if (!is_batch_path(out)) image_format_for(out);
  check_outputs(outputs_of(out));
  const std::vector<SampleBatch> batches = read_batches(inputs);
  std::vector<std::string> read;  // every file merge reads: writing one of them would destroy it
  for (const SampleBatch& b : batches)
    read.insert(read.end(), {b.file.string(), batch_sum_path(written_location(b.file)).string(),
                             batch_count_path(written_location(b.file)).string()});
  if (reference) read.push_back(*reference);
  require_outputs_spare_inputs(outputs_of(out), read);
  // The merged image is held whole: refuse, with the figures, one this machine could not hold.
  if (!batches.empty())
    check_image_fits(out, batches[0].identity.width, batches[0].identity.height, memory_limit());
  MergeOptions options;
  options.spp = spp;
  options.partial = partial;
  MergeResult result = merge_batches(batches, options);

  std::string error;
  const Image image = merged_image(result);
  if (reference) {
    const Image ref = read_pfm(*reference);
    if (ref.width() != image.width() || ref.height() != image.height())
      throw InputError(*reference + ": the reference is " + std::to_string(ref.width()) + "x" +
                       std::to_string(ref.height()) + ", the render " + std::to_string(image.width()) + "x" +
                       std::to_string(image.height()));
    char figure[32];
    std::snprintf(figure, sizeof figure, "%.6g", rmse(image, ref));
    error = std::string("; RMSE ") + figure + " against " + printable(*reference);
  }
  if (is_batch_path(out)) {
    result.merged.file = out;
    write_sample_batch(result.merged);
  } else {
    write_output_image("merge", out, image, encoding);
  }
  const RenderIdentity& id = result.merged.identity;
  std::printf("merge: %zu batch%s of %s %s (%dx%d, seed %llu): %s%s%s; wrote %s\n", batches.size(),
              batches.size() == 1 ? "" : "es", id.program.c_str(),
              id.scene.c_str(), id.width, id.height, static_cast<unsigned long long>(id.seed),
              spp_reached(result).c_str(), result.complete ? ", complete" : ", partial", error.c_str(), out.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Adds sample batches (a stage program's --out NAME.json) into one render: batches of samples, "
               "tiles, or both (docs/scale-out.md)",
               "merge");
  std::string out;
  std::optional<int> spp;
  bool partial = false;
  std::optional<std::string> reference;
  std::vector<std::string> inputs;
  app.add_option("--out", out,
                 "Output: .png, .pfm or .exr (the image) or .json (the merged batch, to merge again later)")
      ->required();
  app.add_option("--spp", spp, "Samples per pixel of the finished render (default: the most any batch reaches)")
      ->transform(decimal(1, kMaxSpp));
  app.add_flag("--partial", partial,
               "Progressive refinement: merge the batches there are, each pixel the mean of the samples it has");
  app.add_option("--reference", reference, "A reference image (PFM) to report the merged render's RMSE against");
  app.add_option("batches", inputs, "Batch descriptions (NAME.json) or folders of them")->required();
  ImageEncoding encoding;
  add_image_encoding_flags(app, encoding);
  if (const std::optional<int> exit_code = parse_command_line(app, argc, argv, "merge")) return *exit_code;
  return run_reporting_errors("merge", [&] { run(out, spp, partial, reference, inputs, encoding); });
}
