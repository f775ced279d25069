// Scale-out end to end: every stage program renders crops and sample batches that the merge
// program adds up to the program's own whole render, and merge refuses, in one line, batches
// that do not add up.
#include "common/image_io.h"
#include "common/metrics.h"

#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;

struct StageProgram {
  const char* name;
  const char* exe;
  const char* scene;
};

const StageProgram kPrograms[] = {
    {"stage1", STAGE1_EXE, "assets/scenes/spheres.json"},
    {"stage2", STAGE2_EXE, "assets/scenes/whitted.json"},
    {"stage3", STAGE3_EXE, "assets/scenes/whitted.json"},
    {"stage4", STAGE4_EXE, "assets/scenes/direct-small-light.json"},
    {"stage5", STAGE5_EXE, "assets/scenes/cornell-box.json"},
};

// 'PROGRAM' followed by a space. (Built by appending: GCC 12 warns falsely of overlapping copies in
// "'" + std::string(...).)
std::string quoted(const char* program) {
  std::string text = "'";
  text += program;
  text += "' ";
  return text;
}

// The program on its scene at 32x24, seed 5, unless `arguments` say otherwise.
std::string command(const StageProgram& p, const std::string& arguments, const char* scene = nullptr,
                    const char* size_and_seed = "--width 32 --height 24 --seed 5") {
  return quoted(p.exe) + "--scene " + source_path(scene ? scene : p.scene).string() + " " + size_and_seed +
         " --threads 2 " + arguments;
}
std::string merge(const std::string& arguments) { return quoted(MERGE_EXE) + arguments; }

// Per pixel and channel within 2 (n + 1) 2^-24 relative (common/batch_merge.h), for n samples.
void expect_equal_up_to_summation_order(const Image& merged, const Image& single, int n, const char* program) {
  ASSERT_EQ(merged.width(), single.width());
  ASSERT_EQ(merged.height(), single.height());
  const double bound = 2.0 * double(n + 1) * std::ldexp(1.0, -24);
  for (size_t i = 0; i < single.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_LE(std::abs(double(merged.pixels()[i][c]) - double(single.pixels()[i][c])),
                bound * std::abs(double(single.pixels()[i][c])))
          << program << ", pixel " << i << ", channel " << c;
}

TEST(ScaleOutPrograms, EveryStageSplitsIntoTilesAndSampleBatchesThatMergeIntoItsRender) {
  for (const StageProgram& p : kPrograms) {
    ScratchDir dir;
    auto run = [&](const std::string& arguments) {
      const auto r = run_command(command(p, arguments), dir);
      ASSERT_EQ(r.exit_code, 0) << p.name << " " << arguments << "\n" << r.err;
    };
    run("--spp 4 --out " + (dir / "whole.pfm").string());
    const Image whole = read_pfm(dir / "whole.pfm");

    // Tiles holding every sample: the whole render, bit for bit.
    std::filesystem::create_directories(dir / "tiles");
    std::filesystem::create_directories(dir / "parts");
    run("--spp 4 --crop 0:32,0:10 --out " + (dir / "tiles/top.json").string());
    run("--spp 4 --crop 0:32,10:24 --out " + (dir / "tiles/bottom.json").string());
    auto r = run_command(merge("--out " + (dir / "tiles.pfm").string() + " " + (dir / "tiles").string()), dir);
    ASSERT_EQ(r.exit_code, 0) << p.name << "\n" << r.err;
    EXPECT_NE(r.out.find("merge: 2 batches of " + std::string(p.name)), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("4 of 4 spp, complete"), std::string::npos) << r.out;
    EXPECT_TRUE(read_pfm(dir / "tiles.pfm") == whole) << p.name;

    // A crop written as an image is that rectangle of the whole render.
    run("--spp 4 --crop 7:19,3:8 --out " + (dir / "crop.pfm").string());
    const Image crop = read_pfm(dir / "crop.pfm");
    ASSERT_EQ(crop.width(), 12);
    ASSERT_EQ(crop.height(), 5);
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 12; ++x) ASSERT_EQ(crop.at(x, y), whole.at(7 + x, 3 + y)) << p.name;

    // Two tiles by two sample ranges, in a shell glob's order.
    for (const char* tile : {"0:32,0:10", "0:32,10:24"})
      for (const char* range : {"0:1", "1:4"})
        run(std::string("--crop ") + tile + " --sample-range " + range + " --out " +
            (dir / "parts" / ("t" + std::string(tile) + "s" + range + ".json")).string());
    r = run_command(merge("--out " + (dir / "parts.pfm").string() + " " + (dir / "parts").string() + "/*.json"), dir);
    ASSERT_EQ(r.exit_code, 0) << p.name << "\n" << r.err;
    expect_equal_up_to_summation_order(read_pfm(dir / "parts.pfm"), whole, 4, p.name);
  }
}

TEST(ScaleOutPrograms, BadRangesAndCropsAreOneLineUsageErrors) {
  for (const StageProgram& p : kPrograms) {
    ScratchDir dir;
    const std::string out = " --out " + (dir / "out.json").string();
    expect_one_line_error(run_command(command(p, "--sample-range 5:2" + out), dir), 2,
                          "--sample-range: 5:2: the range a:b holds samples a to b - 1, so a must be less than b");
    expect_one_line_error(run_command(command(p, "--sample-range 0:4 --spp 4" + out), dir), 2, "excludes");
    expect_one_line_error(run_command(command(p, "--crop '0:4;0:4'" + out), dir), 2, "expected x0:x1,y0:y1");
    // The crop's fit is checked against the image size the scene and the flags give.
    expect_one_line_error(run_command(command(p, "--crop 0:33,0:24" + out), dir), 2,
                          "--crop 0:33,0:24: the window reaches beyond the 32x24 image");
    expect_one_line_error(run_command(command(p, "--out " + (dir / "out.txt").string()), dir), 2,
                          "unknown image format '.txt'");
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
      EXPECT_TRUE(entry.path().filename() == "stdout.txt" || entry.path().filename() == "stderr.txt")
          << p.name << ": a refused run wrote " << entry.path();
  }
}

class MergeProgram : public ::testing::Test {
 protected:
  // Stage 5 batches of samples 0:4, 4:10 and 10:16 of a 32x24 Cornell box, in dir/b0, b1, b2.
  void SetUp() override {
    for (int i = 0; i < 3; ++i) render(kRanges[i], batch_name(i));
  }
  static std::string batch_name(int i) {
    std::string name = "b";  // appended: see quoted()
    name += std::to_string(i);
    return name + ".json";
  }
  void render(const std::string& range, const std::string& name, const std::string& extra = "") {
    const auto r = run_command(command(kPrograms[4], "--sample-range " + range + " " + extra + " --out " +
                                                         (dir / name).string()), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  std::string batch(int i) const { return (dir / batch_name(i)).string(); }
  testing::CommandResult run_merge(const std::string& arguments) {
    return run_command(merge("--out " + (dir / "out.pfm").string() + " " + arguments), dir);
  }
  // The RMSE merge reports against a reference ("...; RMSE 0.0123 against ref.pfm; ...").
  static double reported_rmse(const std::string& out) {
    const size_t at = out.find("RMSE ");
    EXPECT_NE(at, std::string::npos) << out;
    return at == std::string::npos ? 0.0 : std::stod(out.substr(at + 5));
  }

  static constexpr const char* kRanges[] = {"0:4", "4:10", "10:16"};
  ScratchDir dir;
};

TEST_F(MergeProgram, MissingOrDuplicatedBatchesAreOneLineErrors) {
  expect_one_line_error(run_merge(batch(0) + " " + batch(2)), 1, "pixel (0, 0) lacks samples 4:10");
  // The same batch under another name (a copy of its description names the same images).
  std::filesystem::copy_file(batch(1), dir / "copy.json");
  expect_one_line_error(run_merge(batch(0) + " " + batch(1) + " " + batch(2) + " " + (dir / "copy.json").string()), 1,
                        "both hold samples 4:10 of pixels 0:32,0:24: a batch was rendered or given twice");
  expect_one_line_error(run_merge(batch(0) + " " + batch(1) + " " + batch(1) + " " + batch(2)), 1, "given twice");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.pfm"));  // nothing written by a refused merge
}

// Found by trying: a folder of links to batches failed ("cannot open sample batch image"), the
// images looked up beside the link instead of beside the description it names. And an --out
// naming one of those images, reached through the link, must still be refused.
TEST_F(MergeProgram, LinksToBatchesMergeAndTheirImagesAreInputs) {
  std::filesystem::create_directories(dir / "links");
  std::string links;
  for (int i = 0; i < 3; ++i) {
    std::filesystem::create_symlink(dir / batch_name(i), dir / "links" / batch_name(i));
    links += " " + (dir / "links" / batch_name(i)).string();
  }
  const auto merged = run_merge(links);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const auto direct = run_command(merge("--out " + (dir / "direct.pfm").string() + " " + batch(0) + " " + batch(1) +
                                        " " + batch(2)), dir);
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  EXPECT_EQ(testing::read_text(dir / "out.pfm"), testing::read_text(dir / "direct.pfm"));
  const std::string sum = (dir / "b0.sum.pfm").string(), before = testing::read_text(dir / "b0.sum.pfm");
  expect_one_line_error(run_command(merge("--out " + sum + links), dir), 2, "would overwrite the input");
  EXPECT_EQ(testing::read_text(dir / "b0.sum.pfm"), before);
}

TEST_F(MergeProgram, BatchesOfAnotherSceneSeedOrSizeAreRefused) {
  auto render_other = [&](const char* name, const char* scene, const char* size_and_seed) {
    const auto r = run_command(
        command(kPrograms[4], "--sample-range 4:10 --out " + (dir / name).string(), scene, size_and_seed), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  };
  render_other("seed.json", nullptr, "--width 32 --height 24 --seed 6");
  expect_one_line_error(run_merge(batch(0) + " " + (dir / "seed.json").string() + " " + batch(2)), 1,
                        "has seed 6, but");
  render_other("size.json", nullptr, "--width 32 --height 25 --seed 5");
  expect_one_line_error(run_merge(batch(0) + " " + (dir / "size.json").string()), 1, "is of a 32x25 image");
  render_other("scene.json", "assets/scenes/direct-small-light.json", "--width 32 --height 24 --seed 5");
  expect_one_line_error(run_merge(batch(0) + " " + (dir / "scene.json").string()), 1,
                        "direct-small-light.json (fingerprint");
  render("4:10", "options.json", "--integrator nee");
  expect_one_line_error(run_merge(batch(0) + " " + (dir / "options.json").string()), 1, "has options");
  // The default written out is the same render as the default left out.
  render("4:10", "explicit.json", "--integrator mis --sampler sobol");
  EXPECT_EQ(run_merge(batch(0) + " " + (dir / "explicit.json").string() + " " + batch(2)).exit_code, 0);
}

// A wide filter still keeps each sample its own pixel's (filter importance sampling, stage 1): two
// tiles of a Mitchell-filtered render merge into the whole render bit for bit, and a filtered
// batch does not merge with a box-filtered one.
TEST_F(MergeProgram, FilteredTilesMergeIntoTheFilteredRenderAndOnlyWithIt) {
  auto run = [&](const std::string& arguments) {
    const auto r = run_command(command(kPrograms[4], "--filter mitchell " + arguments), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  };
  run("--spp 4 --out " + (dir / "whole.pfm").string());
  run("--spp 4 --crop 0:32,0:10 --out " + (dir / "top.json").string());
  run("--spp 4 --crop 0:32,10:24 --out " + (dir / "bottom.json").string());
  const auto merged = run_merge((dir / "top.json").string() + " " + (dir / "bottom.json").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_TRUE(read_pfm(dir / "out.pfm") == read_pfm(dir / "whole.pfm"));
  run("--sample-range 4:10 --out " + (dir / "mitchell.json").string());
  expect_one_line_error(run_merge(batch(0) + " " + (dir / "mitchell.json").string() + " " + batch(2)), 1, "--filter=mitchell");
}

TEST_F(MergeProgram, BadUsageIsExitTwoAndMissingFilesExitOne) {
  expect_one_line_error(run_command(merge(batch(0)), dir), 2, "--out is required");
  expect_one_line_error(run_command(merge("--out x.txt " + batch(0)), dir), 2, "unknown image format '.txt'");
  expect_one_line_error(run_merge(""), 2, "batches is required");
  expect_one_line_error(run_merge((dir / "none.json").string()), 1, "none.json: cannot open");
  expect_one_line_error(run_merge((dir / "stdout.txt").string()), 2, "not a batch description");
  std::filesystem::create_directory(dir / "empty");
  expect_one_line_error(run_merge((dir / "empty").string()), 1, "no sample batches (*.json) in this folder");
  expect_one_line_error(run_merge("--spp 0 " + batch(0)), 2, "--spp");
  // A batch that claims a 2^20 x 2^20 image: refused with the figures before the image is allocated.
  std::string text = testing::read_text(batch(0));
  for (const auto& [from, to] : {std::pair("\"width\": 32", "\"width\": 1048576"),
                                 std::pair("\"height\": 24", "\"height\": 1048576")}) {
    ASSERT_NE(text.find(from), std::string::npos) << text;
    text.replace(text.find(from), std::string(from).size(), to);
  }
  testing::write_text(dir / "huge.json", text);
  expect_one_line_error(run_merge((dir / "huge.json").string()), 1, "a 1048576x1048576 image has more than 2^31 - 1 pixels");
}

TEST_F(MergeProgram, ProgressiveMergeReportsSamplesPerPixelAndTheError) {
  const auto reference = run_command(command(kPrograms[4], "--spp 256 --out " + (dir / "ref.pfm").string()), dir);
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  const std::string against = " --reference " + (dir / "ref.pfm").string() + " --spp 16 ";
  const auto one = run_merge("--partial" + against + batch(0));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("4 of 16 spp, partial"), std::string::npos) << one.out;
  const auto two = run_merge("--partial" + against + batch(0) + " " + batch(2));
  EXPECT_NE(two.out.find("10 of 16 spp, partial"), std::string::npos) << two.out;
  const auto all = run_merge("--partial" + against + batch(0) + " " + batch(1) + " " + batch(2));
  EXPECT_NE(all.out.find("16 of 16 spp, complete"), std::string::npos) << all.out;
  // More samples, less error (4 to 16 samples: the RMSE about halves).
  EXPECT_LT(reported_rmse(two.out), reported_rmse(one.out));
  EXPECT_LT(reported_rmse(all.out), 0.75 * reported_rmse(one.out));
  // Merging into a batch and that batch with the rest is the same render.
  ASSERT_EQ(run_command(merge("--partial --out " + (dir / "node.json").string() + " " + batch(0) + " " + batch(1)), dir)
                .exit_code,
            0);
  const auto again = run_merge(against + (dir / "node.json").string() + " " + batch(2));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("16 of 16 spp, complete"), std::string::npos) << again.out;
}

TEST(ScaleOutRecipes, ThePlainShellLoopRendersBatchesThatMerge) {
  // docs/scale-out.md's first recipe, as written there, at a small size.
  ScratchDir dir;
  const std::string loop = source_path("tools/scale-out/render-loop.sh").string();
  const std::string scene = " --scene " + source_path("assets/scenes/cornell-box.json").string() +
                            " --width 32 --height 24 --seed 5";
  auto r = run_command("JOBS=2 " + loop + " " + (dir / "parts").string() + " 3 2 " + quoted(STAGE5_EXE) + scene +
                           " --threads 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_command(merge("--spp 6 --out " + (dir / "loop.pfm").string() + " " + (dir / "parts").string()), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 batches of stage5"), std::string::npos) << r.out;
  ASSERT_EQ(run_command(quoted(STAGE5_EXE) + scene + " --spp 6 --out " + (dir / "whole.pfm").string(), dir).exit_code, 0);
  expect_equal_up_to_summation_order(read_pfm(dir / "loop.pfm"), read_pfm(dir / "whole.pfm"), 6, "render-loop.sh");

  // A batch that fails is named, and the loop's exit code says so.
  r = run_command("JOBS=2 " + loop + " " + (dir / "bad").string() + " 2 1 " + quoted(STAGE5_EXE) + scene +
                      " --integrator guess", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("render-loop.sh: batch 1 failed: stage5: error: --integrator"), std::string::npos) << r.err;
}

// Stage 6's path tracer is stage 5's: its batches merge into its render. (Its other methods refuse
// batches and crops: Stage6Cli.WhatAMethodCannotRenderIsOneLine.)
TEST(ScaleOutPrograms, Stage6PathTracingSplitsIntoSampleBatchesThatMerge) {
  ScratchDir dir;
  const StageProgram stage6{"stage6", STAGE6_EXE, "assets/scenes/cornell-box.json"};
  ASSERT_EQ(run_command(command(stage6, "--method pt --spp 4 --out " + (dir / "whole.pfm").string()), dir).exit_code, 0);
  for (const char* range : {"0:3", "3:4"}) {
    const auto r = run_command(command(stage6, std::string("--method pt --sample-range ") + range + " --out " +
                                                   (dir / (std::string("part-") + range[0] + ".json")).string()),
                               dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto r = run_command(merge("--out " + (dir / "merged.pfm").string() + " " + (dir / "part-0.json").string() + " " +
                                   (dir / "part-3.json").string()),
                             dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_equal_up_to_summation_order(read_pfm(dir / "merged.pfm"), read_pfm(dir / "whole.pfm"), 4, "stage6");
}

}  // namespace
}  // namespace rt
