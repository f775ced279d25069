// The stage-5 program: every integrator and both samplers render the Cornell box, the image does
// not depend on the thread count, bad input is one line, and adaptive sampling writes its heat map
// and refuses batches rendered apart.
#include "common/image_io.h"
#include "common/metrics.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <sstream>

namespace rt {
namespace {

using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;

// Built by a stream: GCC 12 warns (-Wrestrict, wrongly) on this chain of string additions once the
// file holds enough of them to be inlined together, which -Werror turns into a build failure.
std::string stage5(const std::string& arguments) {
  std::ostringstream command;
  command << "'" << STAGE5_EXE << "' " << arguments;
  return command.str();
}

const std::string kCornell = source_path("assets/scenes/cornell-box.json").string();

TEST(Stage5Cli, EveryIntegratorAndSamplerRendersTheCornellBox) {
  ScratchDir dir;
  for (const char* integrator : {"naive", "rr", "nee", "mis"})
    for (const char* sampler : {"independent", "sobol"}) {
      const auto out = dir / (std::string(integrator) + "-" + sampler + ".pfm");
      const auto r =
          RT_GRADED(run_command)(stage5("--scene " + kCornell + " --width 32 --height 32 --spp 8 --integrator " +
                                        integrator + " --sampler " + sampler + " --out " + out.string()),
                                 dir);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(r.out.find("NaN"), std::string::npos) << r.out;  // no dropped samples to report
      // The back wall's middle is lit (light sampling finds it at once; BRDF sampling at 8 spp too).
      EXPECT_GT(mean_over(RT_GRADED(read_pfm)(out), PixelRect{12, 8, 20, 16}).x, 0.05)
          << integrator << ", " << sampler << "\n"
          << r.err;  // err names the tasks still missing
    }
}

TEST(Stage5Cli, SameImageForAnyThreadCount) {
  ScratchDir dir;
  for (const char* sampler : {"independent", "sobol"}) {
    const std::string base = "--scene " + kCornell + " --width 40 --height 30 --spp 4 --sampler " + sampler;
    ASSERT_EQ(RT_GRADED(run_command)(stage5(base + " --threads 1 --out " + (dir / "one.pfm").string()), dir).exit_code,
              0);
    ASSERT_EQ(RT_GRADED(run_command)(stage5(base + " --threads 2 --out " + (dir / "two.pfm").string()), dir).exit_code,
              0);
    EXPECT_TRUE(RT_GRADED(read_pfm)(dir / "one.pfm") == RT_GRADED(read_pfm)(dir / "two.pfm")) << sampler;
  }
}

TEST(Stage5Cli, BadInputIsOneLine) {
  ScratchDir dir;
  // Found by trying: --max-depth changed nothing for rr, nee and mis, whose paths end by Russian
  // roulette alone; it is refused there, and taken by naive.
  for (const char* flags : {"--integrator guess", "--sampler halton", "--roulette-start -1", "--max-depth 3",
                            "--integrator rr --max-depth 3", "--integrator nee --max-depth 0"}) {
    const auto usage =
        RT_GRADED(run_command)(stage5("--scene " + kCornell + " " + flags + " --out " + (dir / "o.png").string()), dir);
    EXPECT_EQ(usage.exit_code, 2) << flags << ": " << usage.err;
    EXPECT_FALSE(RT_GRADED(std::filesystem::exists)(dir / "o.png"));
  }
  const auto depth =
      RT_GRADED(run_command)(stage5("--scene " + kCornell + " --max-depth 3 --out " + (dir / "o.png").string()), dir);
  expect_one_line_error(depth, 2, "--max-depth: --integrator mis ends paths by Russian roulette");
  EXPECT_EQ(RT_GRADED(run_command)(stage5("--scene " + kCornell +
                                          " --integrator naive --max-depth 3 --width 8 --height 8 --spp 1 "
                                          "--out " +
                                          (dir / "naive.png").string()),
                                   dir)
                .exit_code,
            0);
  const auto missing = RT_GRADED(run_command)(
      stage5("--scene " + (dir / "none.json").string() + " --out " + (dir / "o.png").string()), dir);
  expect_one_line_error(missing, 1, "none.json");
}

// The scene format allows a lens of radius up to 10^18. Rays from so far away lose the sphere's
// hit point to rounding (NaN), and the next bounce's NaN ray once crashed the 4-wide tree: every
// sample must end, finite or dropped, and the image be written.
TEST(Stage5Cli, AHugeLensRendersWithoutACrash) {
  ScratchDir dir;
  testing::write_text(dir / "lens.json", R"({"render": {"width": 16, "height": 12, "spp": 4},
    "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 40, "aperture_radius": 1e18},
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}],
    "lights": [{"type": "point", "position": [0, 4, -4], "intensity": [10, 10, 10]}]})");
  const auto r = RT_GRADED(run_command)(
      stage5("--scene " + (dir / "lens.json").string() + " --out " + (dir / "o.pfm").string()), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image image = RT_GRADED(read_pfm)(dir / "o.pfm");
  for (const Color& pixel : image.pixels()) EXPECT_TRUE(is_finite(pixel));
}

TEST(Stage5Adaptive, WritesTheImageAndItsHeatMap) {
  ScratchDir dir;
  const std::string scene = source_path("assets/scenes/environment.json").string();
  const auto r = RT_GRADED(run_command)(stage5("--scene " + scene +
                                               " --width 48 --height 27 --spp 64 --adaptive 0.05 "
                                               "--sample-map " +
                                               (dir / "map.png").string() + " --out " + (dir / "o.pfm").string()),
                                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("stage5: adaptive: "), std::string::npos) << r.out;
  EXPECT_TRUE(RT_GRADED(std::filesystem::exists)(dir / "map.png"));
  EXPECT_EQ(RT_GRADED(read_pfm)(dir / "o.pfm").width(), 48);
}

TEST(Stage5Adaptive, RefusesBatchesRenderedApart) {
  ScratchDir dir;
  const std::string scene = source_path("assets/scenes/environment.json").string();
  expect_one_line_error(
      RT_GRADED(run_command)(
          stage5("--scene " + scene + " --adaptive 0.05 --sample-range 0:8 --out " + (dir / "o.json").string()), dir),
      2, "--adaptive: each pixel stops where its own samples say");
  expect_one_line_error(
      RT_GRADED(run_command)(stage5("--scene " + scene + " --adaptive 0.05 --out " + (dir / "o.json").string()), dir),
      2, "--adaptive");
  expect_one_line_error(
      RT_GRADED(run_command)(stage5("--scene " + scene + " --adaptive 0 --out " + (dir / "o.png").string()), dir), 2,
      "--adaptive");
  expect_one_line_error(
      RT_GRADED(run_command)(stage5("--scene " + scene + " --sample-map m.pfm --out " + (dir / "o.png").string()), dir),
      2, "--sample-map");
  EXPECT_FALSE(RT_GRADED(std::filesystem::exists)(dir / "o.json"));
  EXPECT_FALSE(RT_GRADED(std::filesystem::exists)(dir / "o.png"));
}

}  // namespace
}  // namespace rt
