// A sample batch: part of a render kept undivided, so that batches rendered apart (other
// processes, other machines, other days) can be added up into the image of one run
// (common/batch_merge.h, docs/scale-out.md).
//
// On disk a batch is three files beside each other, written in this order, each atomically:
//   NAME.sum.pfm    per pixel of its window, the sum of the samples' radiance (RGB, not divided);
//   NAME.count.pfm  per pixel, how many samples that sum holds (one channel, exact integers);
//   NAME.json       what the batch is: the render it belongs to, its window, which samples of which
//                   pixels it holds, and fingerprints of the two images.
// The description is written last and names the images' fingerprints, so a reader that finds it
// finds the whole batch, and one whose images were replaced since is refused.
#pragma once

#include "common/image.h"
#include "common/sample_sums.h"
#include "common/scene.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rt {

// Samples [begin, end) of a pixel: sample k draws its numbers from (seed, pixel, k).
struct SampleRange {
  int begin = 0, end = 0;

  int count() const { return end - begin; }
  friend bool operator==(const SampleRange&, const SampleRange&) = default;
};

// The samples `samples` of every pixel of `pixels`.
struct BatchPiece {
  PixelRect pixels;
  SampleRange samples;
  friend bool operator==(const BatchPiece&, const BatchPiece&) = default;
};

// What two pieces both hold: the pixels of both and the samples of both (either may be empty).
BatchPiece shared_part(const BatchPiece& a, const BatchPiece& b);
// A pair (i, j), j < i, of pieces that hold some of the same samples of the same pixels, if there
// is one. Takes O(n log n) plus the pixels the pieces cover (covered_pixels), and memory for the
// bounding box of their pixels.
std::optional<std::pair<size_t, size_t>> first_overlap(const std::vector<BatchPiece>& pieces);
// The pixels of all pieces, counted once per piece: what reading, checking and merging them costs.
std::uint64_t covered_pixels(const std::vector<BatchPiece>& pieces);
// More than that is refused (seconds of work: 2^32, e.g. 256 pieces of a 4096 x 4096 image).
inline constexpr std::uint64_t kMaxCoveredPixels = std::uint64_t(1) << 32;

// What makes batches parts of one render. Two batches merge only when all of it agrees but `scene`,
// the path as given, which is kept for messages (the same scene may lie elsewhere on each machine).
struct RenderIdentity {
  std::string program;     // stage1 ... stage5
  std::string scene;       // the scene file as the command line named it
  std::string scene_hash;  // FNV-1a 64 of the scene file's text and of its meshes' data, hex
  std::string options;     // the program's flags that change the image, "--name=value" in order
  int width = 0, height = 0;
  std::uint64_t seed = 0;
};

struct SampleBatch {
  std::filesystem::path file;  // the description (.json) it was read from or is written to
  RenderIdentity identity;
  PixelRect window;                // the pixels `sums` covers: its (0, 0) is the image's (x0, y0)
  std::vector<BatchPiece> pieces;  // disjoint, inside `window`
  bool interrupted = false;        // stopped early: some pixels hold fewer samples than `pieces` say
  SampleSums sums;
};

// The fingerprint a batch records for its scene: FNV-1a 64 of the scene file's text and of the
// data of every mesh it placed (the OBJ files' contents, as read).
std::string scene_fingerprint(const std::filesystem::path& scene_file, const SceneDescription& scene);

// The batch files that belong to a description NAME.json: NAME.sum.pfm and NAME.count.pfm.
std::filesystem::path batch_sum_path(const std::filesystem::path& json);
std::filesystem::path batch_count_path(const std::filesystem::path& json);
// Where a description was written, links followed: its images lie beside it there, so that a folder
// of links to batches (gathered from several machines' outputs) merges.
std::filesystem::path written_location(const std::filesystem::path& json);

// True for a path ending in ".json": a stage program's --out that asks for a batch.
bool is_batch_path(const std::filesystem::path& path);

// Writes the three files of `batch` (to batch.file). Throws InputError naming the file.
void write_sample_batch(const SampleBatch& batch);

// Reads a batch and checks that it is whole and consistent: every field present and in range,
// the pieces disjoint and inside the window and the image, both images of the window's size and
// with the fingerprints the description names, sums finite, and every pixel's count the samples
// its pieces give (fewer allowed only in a batch marked interrupted). Throws InputError
// "FILE: problem" otherwise.
SampleBatch read_sample_batch(const std::filesystem::path& json);

// Per pixel of `window`, the samples the pieces give it (the count a whole batch must have).
std::vector<std::uint32_t> expected_counts(const PixelRect& window, const std::vector<BatchPiece>& pieces);

// "x0:x1,y0:y1" and "a:b", as the command line spells a crop window and a sample range.
std::string format_rect(const PixelRect& rect);
std::string format_range(const SampleRange& range);

}  // namespace rt
