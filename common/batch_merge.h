// Adding sample batches (common/sample_batch.h) into one render: batches of samples, tiles of the
// image, or both, in any number and any order (docs/scale-out.md).
//
// Exactness. Every sample's numbers depend only on (seed, pixel, sample index), so the batches hold
// exactly the samples one run would take. The sums are added in double precision, batch by batch
// in the order of their first sample (then their window's top-left corner), rounded to float once,
// and divided by the count in float, as one run divides. Hence:
//   - one batch with all samples, or tiles that each hold all samples of their pixels, give one
//     run's image bit for bit;
//   - batches that split a pixel's samples give it up to float summation order: one run adds its n
//     samples one after the other in float; merged, each batch's samples are added so and the batch
//     sums then in double. For non-negative radiance each way is within (n - 1) 2^-24 (relative)
//     of the exact sum (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., section 4.2),
//     so the two images differ by at most about 2 (n + 1) 2^-24 relative per pixel.
#pragma once

#include "common/sample_batch.h"

#include <optional>
#include <vector>

namespace rt {

struct MergeOptions {
  // The samples per pixel the finished render has; by default the largest sample index any batch
  // holds, plus one.
  std::optional<int> spp;
  // Progressive refinement: merge what there is. Missing samples and interrupted batches are then
  // allowed; every pixel is the mean of the samples it has (black where none).
  bool partial = false;
};

struct MergeResult {
  // The sum: its window is the bounding box of the batches' windows (the whole image when complete),
  // its pieces theirs together, its identity theirs.
  SampleBatch merged;
  int target_spp = 0;
  std::uint32_t min_spp = 0, max_spp = 0;  // samples per pixel reached, over the whole image
  double mean_spp = 0.0;
  bool complete = false;  // every pixel of the image has all target_spp samples
};

// Adds `batches`. Throws InputError naming the files for: batches of different renders (program,
// scene, options, image size or seed differ); a batch given twice, or two holding the same samples
// of the same pixels; a batch holding samples beyond options.spp; and, unless options.partial,
// missing samples (naming a pixel and the sample ranges no batch holds) or an interrupted batch.
MergeResult merge_batches(const std::vector<SampleBatch>& batches, const MergeOptions& options);

// The merged render as an image of the whole picture: each pixel the mean of its samples, black
// where it has none.
Image merged_image(const MergeResult& result);

}  // namespace rt
