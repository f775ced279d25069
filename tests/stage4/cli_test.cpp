// The stage-4 program: every estimator renders, the image does not depend on the thread count, and
// bad input is one line.
#include "common/image_io.h"
#include "common/metrics.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;
using testing::write_text;

std::string stage4(const std::string& arguments) { return "'" + std::string(STAGE4_EXE) + "' " + arguments; }

const std::string kCornell = source_path("assets/scenes/cornell-box.json").string();

TEST(Stage4Cli, EveryEstimatorRendersTheCornellBox) {
  ScratchDir dir;
  for (const char* estimator : {"uniform", "cosine", "brdf", "light"}) {
    const auto out = dir / (std::string(estimator) + ".pfm");
    const auto r =
        RT_GRADED(run_command)(stage4("--scene " + kCornell + " --width 32 --height 32 --spp 4 --estimator " +
                                      estimator + " --out " + out.string()),
                               dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("1 area emitter,"), std::string::npos) << r.out;
    const Image image = RT_GRADED(read_pfm)(out);
    // The back wall's middle is lit by every estimator (bright on average, nowhere negative).
    EXPECT_GT(mean_over(image, PixelRect{12, 8, 20, 16}).x, 0.05) << estimator << "\n" << r.err;  // err: missing tasks
  }
}

TEST(Stage4Cli, SameImageForAnyThreadCount) {
  ScratchDir dir;
  const std::string base = "--scene " + source_path("assets/scenes/direct-small-light.json").string() +
                           " --width 40 --height 30 --spp 3 --estimator brdf";
  ASSERT_EQ(RT_GRADED(run_command)(stage4(base + " --threads 1 --out " + (dir / "one.pfm").string()), dir).exit_code,
            0);
  ASSERT_EQ(RT_GRADED(run_command)(stage4(base + " --threads 2 --out " + (dir / "two.pfm").string()), dir).exit_code,
            0);
  EXPECT_TRUE(testing::subject([&] { return read_pfm(dir / "one.pfm") == read_pfm(dir / "two.pfm"); }));
}

TEST(Stage4Cli, BadInputIsOneLine) {
  ScratchDir dir;
  write_text(dir / "sky.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40},
    "materials": {"sky": {"emission": [1, 1, 1]}}, "shapes": [{"type": "plane", "point": [0,5,0], "normal": [0,-1,0], "material": "sky"}]})");
  const auto plane = RT_GRADED(run_command)(
      stage4("--scene " + (dir / "sky.json").string() + " --out " + (dir / "o.png").string()), dir);
  expect_one_line_error(plane, 1, "sky.json: /shapes/0: an emitting plane would have infinite power");
  EXPECT_FALSE(testing::subject([&] { return std::filesystem::exists(dir / "o.png"); }));

  write_text(dir / "hot.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40},
    "materials": {"plastic": {"type": "phong", "albedo": [0.8, 0.8, 0.8], "specular": [0.5, 0.5, 0.5]}}, "shapes": []})");
  const auto hot = RT_GRADED(run_command)(
      stage4("--scene " + (dir / "hot.json").string() + " --out " + (dir / "o.png").string()), dir);
  expect_one_line_error(hot, 1, "hot.json: /materials/plastic: albedo + specular exceeds 1");

  const auto usage = RT_GRADED(run_command)(
      stage4("--scene " + kCornell + " --estimator guess --out " + (dir / "o.png").string()), dir);
  EXPECT_EQ(usage.exit_code, 2) << usage.err;
}

}  // namespace
}  // namespace rt
