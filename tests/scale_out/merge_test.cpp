// Merging sample batches (common/batch_merge.h) of real path-traced renders: batches and tiles give
// the single run's image (bit for bit where no pixel's samples are split, up to float summation
// order where they are), and batches that do not add up are refused with what is wrong.
#include "common/program.h"
#include "05-path-tracing/path_render.h"
#include "common/batch_merge.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/sample_batch.h"
#include "common/scene.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <atomic>

namespace rt {
namespace {

constexpr int kWidth = 24, kHeight = 20, kSpp = 16;

// The Cornell box path traced (MIS), so the radiance is non-negative and every pixel's samples vary.
struct CornellRenderer {
  SceneDescription description = load_scene(testing::source_path("assets/scenes/cornell-box.json"));
  LightingScene scene{description, LightingOptions{}};
  Camera camera{description.camera, kWidth, kHeight};

  RenderSettings settings(int first_sample, int spp, std::optional<PixelRect> crop = {}) const {
    RenderSettings s = description.render;
    s.width = kWidth, s.height = kHeight, s.seed = 7;
    s.first_sample = first_sample, s.spp = spp, s.crop = crop;
    return s;
  }
  SampleSums render(const RenderSettings& s, SamplerKind sampler) const {
    SampleGuard guard;
    return render_path_samples(scene, camera, s, PathOptions{}, sampler, 2, guard);
  }
  // A batch as a stage program would write it: `name` stands for its file.
  SampleBatch batch(const std::string& name, int first, int end, SamplerKind sampler = SamplerKind::sobol,
                    std::optional<PixelRect> crop = {}) const {
    const RenderSettings s = settings(first, end - first, crop);
    SampleBatch b;
    b.file = name;
    b.identity = {"stage5", "cornell-box.json", "fingerprint", "--integrator=3", kWidth, kHeight, 7};
    b.window = s.window();
    b.pieces = {{b.window, {first, end}}};
    b.sums = render(s, sampler);
    return b;
  }
  Image single_run(SamplerKind sampler) const { return render(settings(0, kSpp), sampler).mean(); }
};

const CornellRenderer& cornell() {
  static const CornellRenderer renderer;
  return renderer;
}

std::string error_of(const std::vector<SampleBatch>& batches, MergeOptions options = {}) {
  try {
    merge_batches(batches, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(merged)";
}

// One run adds a pixel's n samples one after the other in float; merged, they are added so per
// batch and the batch sums in double. Each is within (n - 1) 2^-24 of the exact sum (relative, for
// non-negative terms), and each division adds one rounding: |merged - single| <= 2 (n + 1) 2^-24.
void expect_equal_up_to_summation_order(const Image& merged, const Image& single, int n) {
  const double bound = 2.0 * double(n + 1) * std::ldexp(1.0, -24);
  int differing = 0;
  for (int y = 0; y < single.height(); ++y)
    for (int x = 0; x < single.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double a = merged.at(x, y)[c], b = single.at(x, y)[c];
        ASSERT_LE(std::abs(a - b), bound * b) << "pixel (" << x << ", " << y << ") channel " << c;
        differing += a != b;
      }
  // Not a vacuous check: the rounding of the two orders does show in some pixels.
  EXPECT_GT(differing, 0);
}

TEST(MergeBatches, BatchesGiveTheSingleRunUpToFloatSummationOrder) {
  for (const SamplerKind sampler : {SamplerKind::sobol, SamplerKind::independent}) {
    const CornellRenderer& c = cornell();
    // Given in any order: the sum's order is fixed by the batches' first samples.
    const MergeResult r = merge_batches(
        {c.batch("c.json", 11, 16, sampler), c.batch("a.json", 0, 5, sampler), c.batch("b.json", 5, 11, sampler)}, {});
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.target_spp, kSpp);
    EXPECT_EQ(r.min_spp, std::uint32_t(kSpp));
    EXPECT_EQ(r.max_spp, std::uint32_t(kSpp));
    expect_equal_up_to_summation_order(merged_image(r), c.single_run(sampler), kSpp);
  }
}

TEST(MergeBatches, BatchesThatRepeatSamplesWouldNotGiveTheSingleRun) {
  // The check above has teeth: three batches of samples 0:5 each (a batch that forgot its first
  // sample index) are a different image, far beyond the rounding bound.
  const CornellRenderer& c = cornell();
  const SampleBatch first = c.batch("a.json", 0, 5);
  SampleBatch again = first, third = c.batch("c.json", 0, 6);
  again.file = "b.json";
  again.pieces = {{again.window, {5, 10}}};
  third.pieces = {{third.window, {10, 16}}};
  const Image merged = merged_image(merge_batches({first, again, third}, {}));
  const Image single = c.single_run(SamplerKind::sobol);
  double largest = 0.0;
  for (size_t i = 0; i < single.pixel_count(); ++i)
    largest = std::max(largest, double(std::abs(merged.pixels()[i].g - single.pixels()[i].g)));
  EXPECT_GT(largest, 1e-3);
}

TEST(MergeBatches, OneBatchWithEverySampleIsTheSingleRunBitForBit) {
  const CornellRenderer& c = cornell();
  EXPECT_TRUE(merged_image(merge_batches({c.batch("all.json", 0, kSpp)}, {})) == c.single_run(SamplerKind::sobol));
}

TEST(MergeBatches, TilesGiveTheSingleRunBitForBit) {
  const CornellRenderer& c = cornell();
  // Uneven tiles, one a single column, one a single row.
  const std::vector<PixelRect> tiles = {{0, 0, 1, 20}, {1, 0, 24, 1}, {1, 1, 13, 20}, {13, 1, 24, 20}};
  std::vector<SampleBatch> batches;
  for (size_t i = 0; i < tiles.size(); ++i)
    batches.push_back(c.batch("tile" + std::to_string(i) + ".json", 0, kSpp, SamplerKind::sobol, tiles[i]));
  const MergeResult r = merge_batches(batches, {});
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.merged.window, (PixelRect{0, 0, kWidth, kHeight}));
  EXPECT_TRUE(merged_image(r) == c.single_run(SamplerKind::sobol));
}

TEST(MergeBatches, TilesOfBatchesGiveTheSingleRun) {
  const CornellRenderer& c = cornell();
  std::vector<SampleBatch> batches;
  for (const PixelRect tile : {PixelRect{0, 0, 24, 9}, PixelRect{0, 9, 24, 20}})
    for (const auto& [a, b] : {std::pair(0, 6), std::pair(6, 16)})
      batches.push_back(c.batch("part" + std::to_string(batches.size()) + ".json", a, b, SamplerKind::sobol, tile));
  expect_equal_up_to_summation_order(merged_image(merge_batches(batches, {})), c.single_run(SamplerKind::sobol), kSpp);
}

TEST(MergeBatches, AMissingBatchIsNamedBySamplesAndPixel) {
  const CornellRenderer& c = cornell();
  const SampleBatch a = c.batch("a.json", 0, 5), b = c.batch("b.json", 5, 11), last = c.batch("c.json", 11, 16);
  EXPECT_EQ(error_of({a, last}),
            "samples missing: 480 of 480 pixels have fewer than 16; pixel (0, 0) lacks samples 5:11, which no "
            "batch holds (render them, or merge with --partial)");
  // The render is meant to have 20 samples per pixel: the last four are missing.
  MergeOptions twenty;
  twenty.spp = 20;
  EXPECT_NE(error_of({a, b, last}, twenty).find("lacks samples 16:20"), std::string::npos);
  // A missing tile: the pixels outside the tiles there are lack every sample.
  const SampleBatch top = c.batch("top.json", 0, kSpp, SamplerKind::sobol, PixelRect{0, 0, 24, 9});
  const std::string missing_tile = error_of({top});
  EXPECT_NE(missing_tile.find("264 of 480 pixels have fewer than 16; pixel (0, 9) lacks samples 0:16"), std::string::npos)
      << missing_tile;
}

TEST(MergeBatches, ADuplicatedBatchIsRefused) {
  const CornellRenderer& c = cornell();
  const SampleBatch a = c.batch("a.json", 0, 5), b = c.batch("b.json", 5, 16);
  SampleBatch copy = b;
  copy.file = "copy-of-b.json";
  EXPECT_EQ(error_of({a, b, copy}),
            "b.json and copy-of-b.json both hold samples 5:16 of pixels 0:24,0:20: a batch was rendered or given twice");
  EXPECT_EQ(error_of({a, b, b}), "b.json: given twice");
  // Overlapping ranges, and overlapping tiles.
  EXPECT_NE(error_of({c.batch("x.json", 0, 8), c.batch("y.json", 5, 16)}).find("both hold samples 5:8"),
            std::string::npos);
  EXPECT_NE(error_of({c.batch("l.json", 0, 16, SamplerKind::sobol, PixelRect{0, 0, 13, 20}),
                      c.batch("r.json", 0, 16, SamplerKind::sobol, PixelRect{12, 0, 24, 20})})
                .find("both hold samples 0:16 of pixels 12:13,0:20"),
            std::string::npos);
}

TEST(MergeBatches, BatchesOfAnotherRenderAreRefused) {
  const CornellRenderer& c = cornell();
  const SampleBatch a = c.batch("a.json", 0, 5);
  auto refused = [&](const std::function<void(RenderIdentity&)>& change, const std::string& message) {
    SampleBatch other = c.batch("other.json", 5, 16);
    change(other.identity);
    const std::string error = error_of({a, other});
    EXPECT_NE(error.find(message), std::string::npos) << error;
    EXPECT_NE(error.find("batches of different renders cannot be merged"), std::string::npos) << error;
  };
  refused([](RenderIdentity& id) { id.seed = 8; }, "other.json: has seed 8, but a.json has seed 7");
  refused([](RenderIdentity& id) { id.scene = "elsewhere.json", id.scene_hash = "another"; },
          "other.json: renders scene elsewhere.json (fingerprint another), but a.json renders cornell-box.json");
  refused([](RenderIdentity& id) { id.width = 48, id.height = 40; }, "is of a 48x40 image, but a.json of a 24x20 one");
  refused([](RenderIdentity& id) { id.program = "stage4"; }, "made by stage4, but a.json by stage5");
  refused([](RenderIdentity& id) { id.options = "--integrator=0"; }, "has options \"--integrator=0\"");
  // The scene's path alone may differ (the same scene lies elsewhere on each machine).
  SampleBatch moved = c.batch("moved.json", 5, 16);
  moved.identity.scene = "/cluster/scratch/cornell-box.json";
  EXPECT_NO_THROW(merge_batches({a, moved}, {}));
}

TEST(MergeBatches, SamplesBeyondTheAskedCountAreRefused) {
  const CornellRenderer& c = cornell();
  MergeOptions eight;
  eight.spp = 8;
  EXPECT_EQ(error_of({c.batch("a.json", 0, 5), c.batch("b.json", 5, 16)}, eight),
            "b.json: holds samples 5:16, beyond the 8 samples per pixel asked for");
}

TEST(MergeBatches, ProgressiveMergeIsTheMeanOfTheSamplesThereAre) {
  const CornellRenderer& c = cornell();
  const SampleBatch a = c.batch("a.json", 0, 5), last = c.batch("c.json", 11, 16);
  MergeOptions partial;
  partial.partial = true;
  partial.spp = 64;
  const MergeResult r = merge_batches({a, last}, partial);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.min_spp, 10u);
  EXPECT_EQ(r.max_spp, 10u);
  EXPECT_EQ(r.mean_spp, 10.0);
  EXPECT_EQ(r.target_spp, 64);
  const Image image = merged_image(r);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      EXPECT_EQ(image.at(x, y), Color(DVec3(a.sums.sum(x, y)) + DVec3(last.sums.sum(x, y))) / 10.0f);

  // One tile of two: the rest of the image has no samples yet and is black.
  const MergeResult half = merge_batches({c.batch("top.json", 0, 16, SamplerKind::sobol, PixelRect{0, 0, 24, 5})}, partial);
  EXPECT_EQ(half.min_spp, 0u);
  EXPECT_EQ(half.max_spp, 16u);
  EXPECT_DOUBLE_EQ(half.mean_spp, 16.0 * 5.0 / 20.0);
  const Image top = merged_image(half);
  EXPECT_EQ(top.width(), kWidth);
  EXPECT_EQ(top.at(3, 12), Color(0.0f));
  EXPECT_GT(top.at(12, 1).r, 0.0f);  // the ceiling light
}

TEST(MergeBatches, AMergedBatchMergesAgain) {
  const CornellRenderer& c = cornell();
  MergeOptions partial;
  partial.partial = true;
  MergeResult first = merge_batches({c.batch("a.json", 0, 5), c.batch("b.json", 5, 11)}, partial);
  first.merged.file = "node1.json";
  EXPECT_EQ(first.merged.pieces.size(), 2u);
  const MergeResult all = merge_batches({first.merged, c.batch("c.json", 11, 16)}, {});
  EXPECT_TRUE(all.complete);
  expect_equal_up_to_summation_order(merged_image(all), c.single_run(SamplerKind::sobol), kSpp);
  // Its pieces still catch a batch given twice.
  EXPECT_NE(error_of({first.merged, c.batch("again.json", 5, 11)}).find("both hold samples 5:11"), std::string::npos);
}

TEST(MergeBatches, AnInterruptedBatchIsMarkedAndMergesOnlyWithPartial) {
  testing::ScratchDir dir;
  const CornellRenderer& c = cornell();
  CommonOptions options;
  options.out = (dir / "stopped.json").string();
  options.threads = 2;
  const RenderSettings s = c.settings(0, 200);
  std::atomic<int> samples{0};
  SampleGuard guard;
  auto radiance = [&](const Ray& ray, Sampler& numbers) {
    if (++samples == 3000) request_interrupt(SIGINT);
    return guard(path_radiance(c.scene, ray, PathOptions{}, numbers));
  };
  const SampleSums sums = render_samples<Rng>(c.camera, s, 2, radiance);
  EXPECT_THROW(write_render("stage5", options, testing::source_path("assets/scenes/cornell-box.json").string(),
                            c.description, s, PixelMeaning::radiance, sums, 1.0),
               Interrupted);
  clear_interrupt();
  const SampleBatch stopped = read_sample_batch(dir / "stopped.json");
  EXPECT_TRUE(stopped.interrupted);
  EXPECT_LT(stopped.sums.total_count(), std::uint64_t(kWidth * kHeight * 200));
  EXPECT_NE(error_of({stopped}).find("stopped.json: interrupted before it finished its samples"), std::string::npos);
  MergeOptions partial;
  partial.partial = true;
  const MergeResult r = merge_batches({stopped}, partial);
  EXPECT_FALSE(r.complete);
  // Stopped in the first pass over the image: the pixels it reached have that pass's samples.
  EXPECT_EQ(r.min_spp, 0u);
  EXPECT_EQ(r.max_spp, std::uint32_t(samples_per_pass(kWidth * kHeight, 200)));
}

}  // namespace
}  // namespace rt
