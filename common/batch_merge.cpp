#include "common/batch_merge.h"

#include "common/error.h"
#include "common/memory_limit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt {
namespace {

std::string name_of(const SampleBatch& b) { return b.file.string(); }

// Batches of one render agree on everything that shapes the image.
void require_same_render(const SampleBatch& first, const SampleBatch& b) {
  const RenderIdentity &x = first.identity, &y = b.identity;
  auto refuse = [&](const std::string& what_b, const std::string& what_first) {
    throw InputError(name_of(b) + ": " + what_b + ", but " + name_of(first) + " " + what_first +
                     ": batches of different renders cannot be merged");
  };
  if (y.program != x.program) refuse("made by " + y.program, "by " + x.program);
  if (y.scene_hash != x.scene_hash)
    refuse("renders scene " + y.scene + " (fingerprint " + y.scene_hash + ")",
           "renders " + x.scene + " (fingerprint " + x.scene_hash + ")");
  if (y.width != x.width || y.height != x.height)
    refuse("is of a " + std::to_string(y.width) + "x" + std::to_string(y.height) + " image",
           "of a " + std::to_string(x.width) + "x" + std::to_string(x.height) + " one");
  if (y.seed != x.seed) refuse("has seed " + std::to_string(y.seed), "has seed " + std::to_string(x.seed));
  if (y.options != x.options) refuse("has options \"" + y.options + "\"", "has \"" + x.options + "\"");
}

// No two pieces may hold the same samples of the same pixel: that is a batch rendered or given
// twice. `owner[i]` is the batch that holds pieces[i].
void require_disjoint(const std::vector<SampleBatch>& batches, const std::vector<BatchPiece>& pieces,
                      const std::vector<size_t>& owner) {
  std::vector<std::pair<std::filesystem::path, size_t>> files;  // sorted, so a repeat is a neighbour
  for (size_t i = 0; i < batches.size(); ++i) files.emplace_back(std::filesystem::weakly_canonical(batches[i].file), i);
  std::sort(files.begin(), files.end());
  for (size_t k = 1; k < files.size(); ++k)
    if (files[k].first == files[k - 1].first) throw InputError(name_of(batches[files[k].second]) + ": given twice");
  if (covered_pixels(pieces) > kMaxCoveredPixels)
    throw InputError("the " + std::to_string(batches.size()) + " batches' pieces cover " +
                     std::to_string(covered_pixels(pieces)) + " pixels in all, more than the " +
                     std::to_string(kMaxCoveredPixels) + " one merge takes (merge them in groups)");
  if (const auto overlap = first_overlap(pieces)) {
    const auto [i, j] = *overlap;
    const BatchPiece both = shared_part(pieces[i], pieces[j]);
    throw InputError(name_of(batches[owner[j]]) + " and " + name_of(batches[owner[i]]) + " both hold samples " +
                     format_range(both.samples) + " of pixels " + format_rect(both.pixels) +
                     ": a batch was rendered or given twice");
  }
}

// Names one pixel that lacks samples and the ranges of [0, spp) that no piece holds for it.
void report_missing(const std::vector<BatchPiece>& pieces, const std::vector<std::uint32_t>& expected,
                    const PixelRect& image, int spp) {
  size_t short_pixels = 0, first = expected.size();
  for (size_t i = 0; i < expected.size(); ++i)
    if (expected[i] < std::uint32_t(spp)) {
      ++short_pixels;
      first = std::min(first, i);
    }
  if (short_pixels == 0) return;
  const int x = int(first % size_t(image.width())), y = int(first / size_t(image.width()));
  std::vector<SampleRange> held;
  for (const BatchPiece& p : pieces)
    if (p.pixels.contains(x, y)) held.push_back(p.samples);
  std::sort(held.begin(), held.end(), [](const SampleRange& a, const SampleRange& b) { return a.begin < b.begin; });
  std::string gaps;
  int next = 0;
  auto gap = [&](int begin, int end) {
    if (begin < end) gaps += (gaps.empty() ? "" : ", ") + format_range({begin, end});
  };
  for (const SampleRange& r : held) {
    gap(next, r.begin);
    next = std::max(next, r.end);
  }
  gap(next, spp);
  throw InputError("samples missing: " + std::to_string(short_pixels) + " of " + std::to_string(expected.size()) +
                   " pixels have fewer than " + std::to_string(spp) + "; pixel (" + std::to_string(x) + ", " +
                   std::to_string(y) + ") lacks samples " + gaps +
                   ", which no batch holds (render them, or merge with --partial)");
}

}  // namespace

MergeResult merge_batches(const std::vector<SampleBatch>& given, const MergeOptions& options) {
  if (given.empty()) throw UsageError("no batches to merge");
  // The order of summation is fixed by the batches, not by the command line.
  std::vector<SampleBatch> batches = given;
  auto first_sample = [](const SampleBatch& b) {
    int first = std::numeric_limits<int>::max();
    for (const BatchPiece& p : b.pieces) first = std::min(first, p.samples.begin);
    return first;
  };
  std::stable_sort(batches.begin(), batches.end(), [&](const SampleBatch& a, const SampleBatch& b) {
    return std::tuple(first_sample(a), a.window.y0, a.window.x0) < std::tuple(first_sample(b), b.window.y0, b.window.x0);
  });

  std::vector<BatchPiece> pieces;
  std::vector<size_t> owner;  // the batch of each piece
  int last_end = 0;
  for (size_t i = 0; i < batches.size(); ++i) {
    require_same_render(batches[0], batches[i]);
    if (batches[i].interrupted && !options.partial)
      throw InputError(name_of(batches[i]) +
                       ": interrupted before it finished its samples (render it again, or merge with --partial)");
    for (const BatchPiece& p : batches[i].pieces) {
      pieces.push_back(p);
      owner.push_back(i);
      last_end = std::max(last_end, p.samples.end);
    }
  }
  const int spp = options.spp.value_or(last_end);
  for (size_t k = 0; k < pieces.size(); ++k)
    if (pieces[k].samples.end > spp)
      throw InputError(name_of(batches[owner[k]]) + ": holds samples " + format_range(pieces[k].samples) +
                       ", beyond the " + std::to_string(spp) + " samples per pixel asked for");
  require_disjoint(batches, pieces, owner);

  const RenderIdentity& id = batches[0].identity;
  const PixelRect image{0, 0, id.width, id.height};
  if (!options.partial) report_missing(pieces, expected_counts(image, pieces), image, spp);

  PixelRect window = batches[0].window;
  for (const SampleBatch& b : batches)
    window = {std::min(window.x0, b.window.x0), std::min(window.y0, b.window.y0), std::max(window.x1, b.window.x1),
              std::max(window.y1, b.window.y1)};
  // The sums are held over the windows' bounding box (and the image, whole, by merged_image).
  check_image_fits(name_of(batches[0]), image.width(), image.height(), memory_limit());
  std::vector<DVec3> sum(window.area(), DVec3(0.0));
  std::vector<std::uint32_t> count(window.area(), 0);
  for (const SampleBatch& b : batches)
    for (int y = 0; y < b.window.height(); ++y)
      for (int x = 0; x < b.window.width(); ++x) {
        const size_t i = size_t(b.window.y0 - window.y0 + y) * size_t(window.width()) + size_t(b.window.x0 - window.x0 + x);
        sum[i] += DVec3(b.sums.sum(x, y));
        count[i] += b.sums.count(x, y);
      }

  MergeResult result;
  result.target_spp = spp;
  SampleBatch& merged = result.merged;
  merged.identity = id;
  merged.window = window;
  merged.pieces = std::move(pieces);
  merged.interrupted = std::any_of(batches.begin(), batches.end(), [](const SampleBatch& b) { return b.interrupted; });
  merged.sums = SampleSums(window.width(), window.height());
  for (int y = 0; y < window.height(); ++y)
    for (int x = 0; x < window.width(); ++x) {
      const size_t i = size_t(y) * size_t(window.width()) + size_t(x);
      const Color total(sum[i]);
      // Each batch's sums are finite floats, but their sum in double may exceed float's range.
      if (!std::isfinite(total.r) || !std::isfinite(total.g) || !std::isfinite(total.b))
        throw InputError("pixel (" + std::to_string(window.x0 + x) + ", " + std::to_string(window.y0 + y) +
                         "): the batches' sums add up to more than float's range (3.4e38): the merged render would "
                         "hold infinities");
      merged.sums.set(x, y, total, count[i]);
    }

  // Samples per pixel over the whole image: pixels outside the window have none.
  const std::uint64_t total = merged.sums.total_count();
  const bool window_is_image = window == image;
  result.min_spp = window_is_image ? *std::min_element(count.begin(), count.end()) : 0;
  result.max_spp = *std::max_element(count.begin(), count.end());
  result.mean_spp = double(total) / double(image.area());
  result.complete = result.min_spp == std::uint32_t(spp);
  return result;
}

Image merged_image(const MergeResult& result) {
  const SampleBatch& m = result.merged;
  const Image window = m.sums.mean();
  Image image(m.identity.width, m.identity.height);
  for (int y = 0; y < window.height(); ++y)
    for (int x = 0; x < window.width(); ++x) image.at(m.window.x0 + x, m.window.y0 + y) = window.at(x, y);
  return image;
}

}  // namespace rt
