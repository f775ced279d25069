// The stage-7 program: every mode renders the Cornell box, and what it cannot render, or a flag
// another mode's, is one line.
#include "common/image_io.h"
#include "common/metrics.h"

#include "support/glowing_room.h"
#include "support/interrupted_render.h"
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <csignal>

namespace rt {
namespace {

using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;

std::string stage7(const std::string& arguments) { return testing::program_command(STAGE7_EXE, arguments); }
using testing::scene_flag;

const std::string kCornell = scene_flag("cornell-box.json");
// VCM's own estimator in every iteration: on the Cornell box the budget it would choose is stage 5's
// path tracer, and these tests are about stage 7's code.
const std::string kEveryTechnique = " --budget all";

TEST(Stage7Cli, EveryModeRendersTheCornellBox) {
  ScratchDir dir;
  for (const char* m : {"vcm", "bpt", "ppm", "lt", "mlt", "pssmlt"}) {
    const auto out = dir / (std::string(m) + ".pfm");
    const bool metropolis = std::string(m).find("mlt") != std::string::npos;
    const std::string budget = metropolis ? " --mutations-per-pixel 32 --bootstrap 5000 --chains 256 --mutation-map " +
                                                (dir / "map.png").string()
                                          : std::string(" --spp 8") + (std::string(m) == "vcm" ? kEveryTechnique : "");
    const auto r = RT_GRADED(run_command)(
        stage7(kCornell + " --width 32 --height 32" + budget + " --mode " + m + " --out " + out.string()), dir);
    ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
    EXPECT_EQ(r.out.find("NaN"), std::string::npos) << r.out;
    // The back wall's middle: the reference is 0.375 there.
    const double back_wall = mean_over(RT_GRADED(read_pfm)(out), PixelRect{18, 7, 23, 12}).x;
    EXPECT_GT(back_wall, 0.25) << m << "\n" << r.err;
    EXPECT_LT(back_wall, 0.6) << m;
    if (metropolis) {
      EXPECT_TRUE(RT_GRADED(std::filesystem::exists)(dir / "map.png")) << m;  // where the chains went
      std::filesystem::remove(dir / "map.png");
    }
  }
}

TEST(Stage7Cli, SamplerPicksTheCameraSubpathsNumbers) {
  // The same seed, the same light subpaths: only the camera's numbers differ, and both images find
  // the back wall.
  ScratchDir dir;
  std::vector<Image> images;
  for (const char* sampler : {"sobol", "independent"}) {
    const auto out = dir / (std::string(sampler) + ".pfm");
    const auto r = RT_GRADED(run_command)(stage7(kCornell + " --width 32 --height 32 --spp 8" + kEveryTechnique +
                                                 " --sampler " + sampler + " --out " + out.string()),
                                          dir);
    ASSERT_EQ(r.exit_code, 0) << sampler << ": " << r.err;
    images.push_back(RT_GRADED(read_pfm)(out));
    const double back_wall = mean_over(images.back(), PixelRect{18, 7, 23, 12}).x;
    EXPECT_GT(back_wall, 0.25) << sampler;
    EXPECT_LT(back_wall, 0.6) << sampler;
  }
  EXPECT_FALSE(images[0] == images[1]);
}

TEST(Stage7Cli, TheBudgetIsChosenByTheFirstIterationOrGiven) {
  // By default the first iteration reports its estimates and its choice; a budget given runs from
  // the first iteration on and reports nothing.
  ScratchDir dir;
  const std::string flags = kCornell + " --width 32 --height 32 --spp 4 --out " + (dir / "o.pfm").string();
  const auto chosen = RT_GRADED(run_command)(stage7(flags), dir);
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_NE(chosen.out.find("<- chosen"), std::string::npos) << chosen.out;
  for (const char* word : {"all", "pt", "1", "8cm"}) {
    const auto given = RT_GRADED(run_command)(stage7(flags + " --budget " + word), dir);
    ASSERT_EQ(given.exit_code, 0) << word << ": " << given.err;
    EXPECT_EQ(given.out.find("chosen"), std::string::npos) << word << ": " << given.out;
  }
}

TEST(Stage7Cli, WhatItCannotRenderIsOneLine) {
  ScratchDir dir;
  const std::string out = " --width 8 --height 8 --out " + (dir / "o.png").string();
  std::string lens = RT_GRADED(testing::read_text)(source_path("assets/scenes/cornell-box.json"));
  lens.replace(lens.find("\"vfov\""), 0, "\"aperture_radius\": 5, ");
  testing::write_text(dir / "lens.json", lens);
  struct Case {
    std::string flags;
    int code;
    const char* says;
  };
  const Case cases[] = {
      {kCornell + " --mode guess", 2, "--mode"},
      {kCornell + " --alpha 0", 2, "--alpha"},
      {kCornell + " --alpha 1.5", 2, "--alpha"},
      {kCornell + " --radius -1", 2, "--radius"},
      // Paths end by Russian roulette alone: only multiplexed MLT has a depth to limit.
      {kCornell + " --max-depth 2", 2, "--max-depth is for --mode mlt"},
      {kCornell + " --mode pssmlt --max-depth 2", 2, "--max-depth is for --mode mlt"},
      {kCornell + " --mode mlt --radius 1", 2, "--radius is for --mode vcm and ppm"},
      {kCornell + " --mode lt --alpha 0.5", 2, "--alpha is for --mode vcm and ppm"},
      {kCornell + " --mode lt --sampler sobol", 2, "--sampler is for --mode vcm, bpt and ppm"},
      {kCornell + " --mode pssmlt --sampler independent", 2, "--sampler is for --mode vcm, bpt and ppm"},
      {kCornell + " --sampler halton", 2, "--sampler"},
      {kCornell + " --mode bpt --budget all", 2, "--budget is for --mode vcm"},
      {kCornell + " --budget some", 2, "--budget"},
      {kCornell + " --chains 8", 2, "--chains is for --mode mlt and pssmlt"},
      {kCornell + " --mode ppm --bootstrap 8", 2, "--bootstrap is for --mode mlt and pssmlt"},
      {kCornell + " --mode mlt --mutations-per-pixel 0", 2, "--mutations-per-pixel"},
      {kCornell + " --mode mlt --large-step 1.5", 2, "--large-step"},
      {kCornell + " --mutation-map m.png", 2, "--mutation-map is for --mode mlt and pssmlt"},
      {kCornell + " --mode mlt --mutation-map m.pfm", 2, "--mutation-map: the heat map is a picture"},
      {kCornell + " --crop 0:4,0:4", 2, "cannot be rendered in batches or windows"},
      {kCornell + " --mode ppm --sample-range 0:1", 2, "cannot be rendered in batches or windows"},
      {kCornell + " --filter gaussian", 2, "--filter: stage7 uses the box filter"},
      {scene_flag("cornell-box-point-light.json"), 1, "a point light has no area"},
      {scene_flag("environment.json") + " --mode ppm", 1, "environment light"},
      {"--scene " + (dir / "lens.json").string() + " --mode lt", 1, "this camera has an aperture"},
  };
  for (const Case& c : cases) {
    const auto r = RT_GRADED(run_command)(stage7(c.flags + out), dir);
    expect_one_line_error(r, c.code, c.says);
    EXPECT_FALSE(RT_GRADED(std::filesystem::exists)(dir / "o.png")) << c.flags;
  }
  const auto batch =
      RT_GRADED(run_command)(stage7(kCornell + " --width 8 --height 8 --out " + (dir / "b.json").string()), dir);
  expect_one_line_error(batch, 2, "cannot be rendered in batches or windows");
}

TEST(Stage7Cli, CtrlCKeepsWhatWasRendered) {
  for (const std::vector<std::string>& mode :
       {std::vector<std::string>{"--mode", "vcm", "--budget", "all", "--spp", "1048576"},
        std::vector<std::string>{"--mode", "mlt", "--mutations-per-pixel", "1000000", "--bootstrap", "2000"}}) {
    ScratchDir dir;
    testing::write_text(dir / "room.json", testing::kGlowingRoom);
    const auto out = dir / "partial.pfm";
    std::vector<std::string> command{
        STAGE7_EXE, "--scene",   (dir / "room.json").string(), "--width", "48", "--height", "48", "--threads", "2",
        "--out",    out.string()};
    command.insert(command.end(), mode.begin(), mode.end());
    const auto [started, ended, exit_code, said, image] =
        testing::subject([&] { return testing::interrupt_render(command, dir.path(), out); });
    ASSERT_TRUE(started);
    ASSERT_TRUE(ended) << mode[1] << ": still running two seconds after Ctrl-C";
    EXPECT_EQ(exit_code, 128 + SIGINT) << mode[1];
    EXPECT_NE(said.find("stage7: interrupted by"), std::string::npos) << said;
    // The glowing room's radiance is L = Le / (1 - albedo) = 2 everywhere: the iterations or chains
    // that finished are kept whole, so the image's mean is 2 up to noise.
    double sum = 0.0;
    for (const Color& c : image.pixels()) sum += c.x;
    ASSERT_FALSE(image.pixels().empty()) << mode[1];
    EXPECT_NEAR(sum / double(image.pixels().size()), 2.0, 0.2) << mode[1];
  }
}

}  // namespace
}  // namespace rt
