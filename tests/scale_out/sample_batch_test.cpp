// Sample batch files (common/sample_batch.h) and the flags that ask for one: a batch reads back
// bit for bit, and a damaged, replaced or inconsistent one is refused naming its file.
#include "common/options.h"
#include "common/error.h"
#include "common/image_io.h"
#include "common/sample_batch.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rt {
namespace {

using testing::read_text;
using testing::ScratchDir;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ScaleOutFlags, SampleRangesAndCropsParseAndBadOnesAreUsageErrors) {
  const SampleRangeFlag r = parse_sample_range("3:10");
  EXPECT_EQ(r.first, 3);
  EXPECT_EQ(r.count, 7);
  EXPECT_EQ(parse_sample_range("0:1").count, 1);
  for (const char* bad : {"3:3", "5:2", "a:b", "-1:3", "3", "1:2000000", ":4", "1:4:5", " 1:4"})
    EXPECT_THROW(parse_sample_range(bad), UsageError) << bad;
  EXPECT_EQ(error_of([] { parse_sample_range("5:2"); }),
            "--sample-range 5:2: the range a:b holds samples a to b - 1, so a must be less than b");

  EXPECT_EQ(parse_crop("0:1,5:9", 64, 48), (PixelRect{0, 5, 1, 9}));
  EXPECT_EQ(parse_crop("0:64,0:48", 64, 48), (PixelRect{0, 0, 64, 48}));
  for (const char* bad : {"0:65,0:4", "0:4,0:49", "4:4,0:4", "5:4,0:4", "0:4", "0:4;0:4", "-1:4,0:4", "0:4,0:x"})
    EXPECT_THROW(parse_crop(bad, 64, 48), UsageError) << bad;
  EXPECT_EQ(error_of([] { parse_crop("0:65,0:4", 64, 48); }),
            "--crop 0:65,0:4: the window reaches beyond the 64x48 image");
}

// A batch of a 7x5 image holding samples 4:10 of the window 2:6,1:4, with sums that exercise
// every float: tiny, huge, zero.
SampleBatch example_batch(const std::filesystem::path& file) {
  SampleBatch b;
  b.file = file;
  b.identity = {"stage5", "scenes/a.json", "0123456789abcdef", "--integrator=3 --max-depth=5", 7, 5, 42};
  b.window = {2, 1, 6, 4};
  b.pieces = {{b.window, {4, 10}}};
  b.sums = SampleSums(4, 3);
  const float values[] = {0.0f, 1e-38f, 3.5f, 1e30f, 0.1f, 7.25f};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      b.sums.set(x, y, Color(values[(x + y) % 6], values[(x + 2 * y + 1) % 6], float(x * y)), 6);
  return b;
}

TEST(SampleBatchFile, ReadsBackBitForBit) {
  ScratchDir dir;
  const SampleBatch written = example_batch(dir / "part.json");
  write_sample_batch(written);
  EXPECT_TRUE(std::filesystem::exists(dir / "part.sum.pfm"));
  EXPECT_TRUE(std::filesystem::exists(dir / "part.count.pfm"));
  const SampleBatch read = read_sample_batch(dir / "part.json");
  EXPECT_EQ(read.identity.program, "stage5");
  EXPECT_EQ(read.identity.scene, "scenes/a.json");
  EXPECT_EQ(read.identity.scene_hash, "0123456789abcdef");
  EXPECT_EQ(read.identity.options, "--integrator=3 --max-depth=5");
  EXPECT_EQ(read.identity.width, 7);
  EXPECT_EQ(read.identity.height, 5);
  EXPECT_EQ(read.identity.seed, 42u);
  EXPECT_EQ(read.window, written.window);
  EXPECT_EQ(read.pieces, written.pieces);
  EXPECT_FALSE(read.interrupted);
  EXPECT_TRUE(read.sums.sums() == written.sums.sums());
  EXPECT_EQ(read.sums.counts(), written.sums.counts());
  // The sum image is the undivided sum a PFM viewer can show; the count image a one-channel PFM.
  EXPECT_TRUE(read_pfm(dir / "part.sum.pfm") == written.sums.sums());
  EXPECT_EQ(read_text(dir / "part.count.pfm").substr(0, 3), "Pf\n");
}

// Writes the example batch after `damage` and expects reading it to fail with `message`, which
// starts with the name of the batch's file at fault (the description, or a missing image).
void expect_refused(const std::function<void(SampleBatch&)>& damage, const std::string& message,
                    const std::function<void(const ScratchDir&)>& damage_files = nullptr) {
  ScratchDir dir;
  SampleBatch b = example_batch(dir / "part.json");
  damage(b);
  write_sample_batch(b);
  if (damage_files) damage_files(dir);
  const std::string error = error_of([&] { read_sample_batch(dir / "part.json"); });
  EXPECT_EQ(error.rfind((dir / "part.").string(), 0), 0u) << error;
  EXPECT_NE(error.find(message), std::string::npos) << error;
}

TEST(SampleBatchFile, InconsistentBatchesAreRefusedNamingTheFile) {
  auto none = [](SampleBatch&) {};
  // Counts that do not match the pieces: a sample too many, one missing without an interruption.
  expect_refused([](SampleBatch& b) { b.sums.set(1, 2, Color(1.0f), 7); },
                 "pixel (3, 3) holds 7 samples, but the pieces give it 6");
  expect_refused([](SampleBatch& b) { b.sums.set(0, 0, Color(1.0f), 5); },
                 "pixel (2, 1) holds 5 samples, but the pieces give it 6");
  expect_refused([](SampleBatch& b) { b.sums.set(3, 1, Color(std::numeric_limits<float>::quiet_NaN()), 6); },
                 "pixel (5, 2) has a sum that is not finite");
  expect_refused([](SampleBatch& b) { b.pieces.push_back({{2, 1, 3, 2}, {9, 12}}); },
                 "two pieces both hold samples of pixels 2:3,1:2");
  expect_refused([](SampleBatch& b) { b.pieces = {{{0, 0, 3, 3}, {4, 10}}}; }, "lie outside the window");
  expect_refused([](SampleBatch& b) { b.window = {2, 1, 8, 4}; }, "\"window.x\" is 2:8, not a non-empty range within 0:7");
  expect_refused([](SampleBatch& b) { b.pieces = {{b.window, {10, 4}}}; }, "\"samples\" is 10:4");
  // Files replaced, damaged or missing since the description was written.
  expect_refused(none, "part.sum.pfm is not the image this description was written with",
                 [](const ScratchDir& dir) {
                   std::string bytes = read_text(dir / "part.sum.pfm");
                   bytes.back() ^= 1;
                   testing::write_text(dir / "part.sum.pfm", bytes);
                 });
  expect_refused(none, "part.count.pfm: cannot open",
                 [](const ScratchDir& dir) { std::filesystem::remove(dir / "part.count.pfm"); });
  expect_refused(none, "malformed JSON", [](const ScratchDir& dir) {
    const std::string text = read_text(dir / "part.json");
    testing::write_text(dir / "part.json", text.substr(0, text.size() / 2));
  });
  expect_refused(none, "missing \"seed\"", [](const ScratchDir& dir) {
    std::string text = read_text(dir / "part.json");
    text.erase(text.find("  \"seed\""), text.find('\n', text.find("  \"seed\"")) - text.find("  \"seed\"") + 1);
    testing::write_text(dir / "part.json", text);
  });
}

TEST(SampleBatchFile, ReadingAFileThatIsNoBatchSaysSo) {
  const std::string scene = testing::source_path("assets/scenes/cornell-box.json").string();
  EXPECT_EQ(error_of([&] { read_sample_batch(scene); }),
            scene + ": not a sample batch description (no \"format\": \"rt sample batch 1\")");
}

TEST(SampleBatchFile, AnInterruptedBatchMayHoldFewerSamples) {
  ScratchDir dir;
  SampleBatch b = example_batch(dir / "part.json");
  b.interrupted = true;
  b.sums.set(3, 2, Color(0.0f), 0);
  b.sums.set(2, 2, Color(2.0f), 3);
  write_sample_batch(b);
  const SampleBatch read = read_sample_batch(dir / "part.json");
  EXPECT_TRUE(read.interrupted);
  EXPECT_EQ(read.sums.count(3, 2), 0u);
  EXPECT_EQ(read.sums.count(2, 2), 3u);
  EXPECT_EQ(read.sums.mean().at(2, 2), Color(2.0f / 3.0f));
  EXPECT_EQ(read.sums.mean().at(3, 2), Color(0.0f));  // no samples: black, not NaN
}

TEST(SampleBatchFile, ExpectedCountsAddThePiecesOverTheWindow) {
  const std::vector<BatchPiece> pieces = {{{0, 0, 2, 1}, {0, 4}}, {{1, 0, 3, 2}, {4, 5}}};
  EXPECT_EQ(expected_counts({0, 0, 3, 2}, pieces), (std::vector<std::uint32_t>{4, 5, 1, 0, 1, 1}));
  EXPECT_EQ(expected_counts({1, 1, 3, 2}, pieces), (std::vector<std::uint32_t>{1, 1}));
}

}  // namespace
}  // namespace rt
