// The stage-6 program: every method renders the Cornell box, one BDPT strategy renders alone, the
// image does not depend on the thread count, Ctrl-C keeps what was rendered, and what a method
// cannot render is one line.
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

std::string stage6(const std::string& arguments) { return testing::program_command(STAGE6_EXE, arguments); }
using testing::scene_flag;

const std::string kCornell = scene_flag("cornell-box.json");

TEST(Stage6Cli, EveryMethodRendersTheCornellBox) {
  ScratchDir dir;
  for (const char* m : {"pt", "lt", "bdpt", "sppm"}) {
    const auto out = dir / (std::string(m) + ".pfm");
    const auto r = RT_GRADED(run_command)(
        stage6(kCornell + " --width 32 --height 32 --spp 8 --photons 20000 --method " + m + " --out " + out.string()),
        dir);
    ASSERT_EQ(r.exit_code, 0) << m << ": " << r.err;
    EXPECT_EQ(r.out.find("NaN"), std::string::npos) << r.out;  // no dropped samples to report
    // The back wall's middle: the reference is 0.375 there; 8 samples of any method find most of it.
    const double back_wall = mean_over(RT_GRADED(read_pfm)(out), PixelRect{18, 7, 23, 12}).x;
    EXPECT_GT(back_wall, 0.25) << m << "\n" << r.err;  // err names the tasks still missing
    EXPECT_LT(back_wall, 0.6) << m;
  }
}

TEST(Stage6Cli, OneStrategyRendersAlone) {
  // (1, 2) is next-event estimation at the first hit: direct light only, so the image is lit but
  // darker than all strategies together, which add the indirect light.
  ScratchDir dir;
  const std::string base = kCornell + " --width 24 --height 24 --spp 16 --method bdpt";
  const auto one = RT_GRADED(run_command)(stage6(base + " --strategy 1,2 --out " + (dir / "direct.pfm").string()), dir);
  const auto every = RT_GRADED(run_command)(stage6(base + " --out " + (dir / "all.pfm").string()), dir);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(every.exit_code, 0) << every.err;
  const PixelRect all{0, 0, 24, 24};
  const double direct = mean_over(RT_GRADED(read_pfm)(dir / "direct.pfm"), all).x,
               total = mean_over(RT_GRADED(read_pfm)(dir / "all.pfm"), all).x;
  EXPECT_GT(direct, 0.05) << one.err;  // err names the tasks still missing
  EXPECT_LT(direct, 0.85 * total) << every.err;
}

TEST(Stage6Cli, SameImageForAnyThreadCount) {
  ScratchDir dir;
  for (const char* m : {"lt", "bdpt", "sppm"}) {
    const std::string base = kCornell + " --width 40 --height 30 --spp 4 --photons 5000 --method " + m;
    ASSERT_EQ(RT_GRADED(run_command)(stage6(base + " --threads 1 --out " + (dir / "one.pfm").string()), dir).exit_code,
              0);
    ASSERT_EQ(RT_GRADED(run_command)(stage6(base + " --threads 2 --out " + (dir / "two.pfm").string()), dir).exit_code,
              0);
    EXPECT_TRUE(RT_GRADED(read_pfm)(dir / "one.pfm") == RT_GRADED(read_pfm)(dir / "two.pfm")) << m;
  }
}

TEST(Stage6Cli, WhatAMethodCannotRenderIsOneLine) {
  ScratchDir dir;
  const std::string out = " --width 8 --height 8 --out " + (dir / "o.png").string();
  // The Cornell box seen through a lens.
  std::string lens = RT_GRADED(testing::read_text)(source_path("assets/scenes/cornell-box.json"));
  lens.replace(lens.find("\"vfov\""), 0, "\"aperture_radius\": 5, ");
  testing::write_text(dir / "lens.json", lens);
  const std::string lens_scene = "--scene " + (dir / "lens.json").string();
  struct Case {
    std::string flags;
    int code;
    const char* says;
  };
  const Case cases[] = {
      {kCornell + " --method guess", 2, "--method"},
      {kCornell + " --method bdpt --strategy 0,1", 2, "--strategy: expected s,t"},
      {kCornell + " --method bdpt --strategy 2", 2, "--strategy: expected s,t"},
      {kCornell + " --method sppm --strategy 1,1", 2, "--strategy is for --method bdpt"},
      {kCornell + " --method sppm --photons 0", 2, "--photons"},
      {kCornell + " --method sppm --alpha 0", 2, "--alpha"},
      {kCornell + " --method sppm --alpha 1.5", 2, "--alpha"},
      {kCornell + " --method sppm --radius -1", 2, "--radius"},
      // Found by trying: --max-depth changed nothing in lt and bdpt (nor in pt), whose paths end by
      // Russian roulette alone.
      {kCornell + " --method bdpt --max-depth 2", 2, "--max-depth: --method bdpt ends paths by Russian roulette"},
      {kCornell + " --method lt --max-depth 16", 2, "--max-depth: --method lt ends paths by Russian roulette"},
      {kCornell + " --method pt --max-depth 1000", 2, "--max-depth: --method pt ends paths by Russian roulette"},
      {kCornell + " --method bdpt --crop 0:4,0:4", 2, "cannot be rendered in batches or windows"},
      {kCornell + " --method lt --sample-range 0:1", 2, "cannot be rendered in batches or windows"},
      {kCornell + " --method bdpt --filter gaussian", 2, "--filter: lt, bdpt and sppm use the box filter"},
      {kCornell + " --method sppm --filter tent", 2, "--filter: lt, bdpt and sppm use the box filter"},
      {scene_flag("cornell-box-point-light.json") + " --method bdpt", 1, "a point light has no area"},
      {scene_flag("environment.json") + " --method sppm", 1, "environment light"},
      {lens_scene + " --method lt", 1, "this camera has an aperture"},
  };
  for (const Case& c : cases) {
    const auto r = RT_GRADED(run_command)(stage6(c.flags + out), dir);
    expect_one_line_error(r, c.code, c.says);
    EXPECT_FALSE(RT_GRADED(std::filesystem::exists)(dir / "o.png")) << c.flags;
  }
  // A batch file is refused too, before anything is rendered.
  const auto batch = RT_GRADED(run_command)(
      stage6(kCornell + " --method sppm --width 8 --height 8 --out " + (dir / "b.json").string()), dir);
  expect_one_line_error(batch, 2, "cannot be rendered in batches or windows");
  // The path tracer takes what the others cannot: a point light, a lens.
  for (const std::string& scene : {scene_flag("cornell-box-point-light.json"), lens_scene})
    EXPECT_EQ(RT_GRADED(run_command)(stage6(scene + " --method pt --spp 4" + out), dir).exit_code, 0) << scene;
  EXPECT_EQ(RT_GRADED(run_command)(stage6(lens_scene + " --method sppm --spp 2 --photons 1000" + out), dir).exit_code,
            0);
  EXPECT_EQ(RT_GRADED(run_command)(stage6(kCornell + " --method sppm --max-depth 2 --spp 1 --photons 1000" + out), dir)
                .exit_code,
            0);
}

TEST(Stage6Cli, CtrlCKeepsWhatWasRendered) {
  for (const char* m : {"bdpt", "sppm"}) {
    ScratchDir dir;
    testing::write_text(dir / "room.json", testing::kGlowingRoom);
    const auto out = dir / "partial.pfm";
    // The run as the test saw it: started, ended within two seconds of Ctrl-C, its exit code (-1
    // when a signal ended it), what it printed and the image it wrote.
    const auto [started, ended, exit_code, said, image] = testing::subject([&] {
      return testing::interrupt_render(
          {STAGE6_EXE, "--scene", (dir / "room.json").string(), "--width", "48", "--height", "48", "--spp", "1048576",
           "--photons", "2000", "--threads", "2", "--method", m, "--out", out.string()},
          dir.path(), out);
    });
    ASSERT_TRUE(started);
    ASSERT_TRUE(ended) << m << ": still running two seconds after Ctrl-C";
    EXPECT_EQ(exit_code, 128 + SIGINT) << m;
    EXPECT_NE(said.find("stage6: interrupted by"), std::string::npos) << said;
    // Every pixel the render reached shows the glowing room's radiance L = Le / (1 - albedo) = 2, up
    // to noise (a stop during the first pass leaves the pixels it had not reached black, as in
    // every stage; a splat that landed on one of those is dropped with it).
    double sum = 0.0;
    int reached = 0;
    for (const Color& c : image.pixels())
      if (c.x > 0.0f) sum += c.x, ++reached;
    ASSERT_GT(reached, 0) << m;  // how many depends on the machine's speed (sanitizers: a tenth of it)
    EXPECT_NEAR(sum / reached, 2.0, 0.2) << m;
  }
}

}  // namespace
}  // namespace rt
