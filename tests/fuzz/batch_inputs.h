// What the batch and merge fuzz targets, and the replay of their inputs in the normal test suite,
// share: a folder with one fixed pair of batch images (a 2 x 2 window, 4 samples per pixel), and
// the reading of descriptions that name them. A description is what the fuzzer changes; the
// images stay valid, so that it gets past the fingerprint check to everything behind it (the
// corpus's descriptions carry the images' fingerprints).
#pragma once

#include "common/batch_merge.h"
#include "common/error.h"
#include "common/sample_batch.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace rt::fuzzing {

// Writes fuzz.sum.pfm and fuzz.count.pfm into `folder`, through write_sample_batch, with their
// description fuzz.json (the seed tests/fuzz/corpus/batch/ holds).
inline void write_batch_images(const std::filesystem::path& folder) {
  SampleBatch batch;
  batch.file = folder / "fuzz.json";
  batch.identity = {"stage5", "cornell-box.json", "00112233aabbccdd", "--integrator=mis", 2, 2, 7};
  batch.window = {0, 0, 2, 2};
  batch.pieces = {{{0, 0, 2, 2}, {0, 4}}};
  batch.sums = SampleSums(2, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) batch.sums.set(x, y, Color(0.25f * float(x + 1), 0.5f, 0.125f * float(y + 1)), 4);
  write_sample_batch(batch);
}

// The fuzz targets' folder: made once per process, in the temporary directory.
inline std::filesystem::path fuzz_folder() {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("rt-fuzz-batch-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  write_batch_images(folder);
  return folder;
}

// Writes `text` as a description beside the images and reads it: a batch, or InputError.
inline SampleBatch read_batch_text(const std::filesystem::path& folder, std::string_view text, const std::string& name) {
  const std::filesystem::path file = folder / name;
  std::ofstream(file, std::ios::binary).write(text.data(), std::streamsize(text.size()));
  return read_sample_batch(file);
}

// A merge input: descriptions separated by lines "---", after a first line "--partial" for a
// partial merge. Every description that reads is merged.
inline void merge_batch_texts(const std::filesystem::path& folder, std::string_view input) {
  MergeOptions options;
  constexpr std::string_view kPartial = "--partial\n";
  options.partial = input.substr(0, kPartial.size()) == kPartial;
  if (options.partial) input.remove_prefix(kPartial.size());
  std::vector<SampleBatch> batches;
  size_t start = 0;
  for (int part = 0; start <= input.size() && part < 16; ++part) {
    const size_t end = std::min(input.find("\n---\n", start), input.size());
    try {
      batches.push_back(read_batch_text(folder, input.substr(start, end - start), "part" + std::to_string(part) + ".json"));
    } catch (const InputError&) {
    }
    start = end + 5;
  }
  if (batches.empty()) return;
  try {
    merged_image(merge_batches(batches, options));
  } catch (const InputError&) {
  } catch (const UsageError&) {
  }
}

}  // namespace rt::fuzzing
