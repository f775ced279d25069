// The stage-1 program as a user meets it: exit codes, one-line errors, no partial output.
#include "common/image_io.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;
using testing::subject;

const std::string kStage1 = STAGE1_EXE;
const std::string kSpheres = source_path("assets/scenes/spheres.json").string();

std::string stage1(const std::string& arguments) { return "'" + kStage1 + "' " + arguments; }

TEST(Stage1Cli, HelpListsTheCommonFlags) {
  ScratchDir dir;
  const auto r = subject([&] { return run_command(stage1("--help"), dir); });
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--scene", "--spp", "--out", "--width", "--height", "--threads", "--seed", "--debug"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST(Stage1Cli, RendersPngAndPfm) {
  ScratchDir dir;
  const auto png = subject([&] {
    return run_command(
        stage1("--scene " + kSpheres + " --width 40 --height 25 --spp 2 --out " + (dir / "a.png").string()), dir);
  });
  EXPECT_EQ(png.exit_code, 0) << png.err;
  EXPECT_EQ(png.err, "") << "no progress output when stderr is not a terminal";
  EXPECT_TRUE(subject([&] { return std::filesystem::exists(dir / "a.png"); }));
  const auto pfm = subject([&] {
    return run_command(
        stage1("--scene " + kSpheres + " --width 40 --height 25 --spp 2 --threads 1 --out " + (dir / "a.pfm").string()),
        dir);
  });
  EXPECT_EQ(pfm.exit_code, 0) << pfm.err;
  const Image image = subject([&] { return read_pfm(dir / "a.pfm"); });
  EXPECT_EQ(image.width(), 40);
  EXPECT_EQ(image.height(), 25);
}

TEST(Stage1Cli, DebugViews) {
  ScratchDir dir;
  for (const char* view : {"normal", "depth", "albedo"}) {
    const auto r = subject([&] {
      return run_command(stage1("--scene " + kSpheres + " --width 20 --height 10 --spp 1 --debug " + view + " --out " +
                                (dir / (std::string(view) + ".png")).string()),
                         dir);
    });
    EXPECT_EQ(r.exit_code, 0) << view << ": " << r.err;
  }
  const auto bad = subject([&] {
    return run_command(stage1("--scene " + kSpheres + " --debug curvature --out " + (dir / "x.png").string()), dir);
  });
  expect_one_line_error(bad, 2, "--debug");
}

TEST(Stage1Cli, BadUsageExitsWithTwo) {
  ScratchDir dir;
  const std::string out = " --out " + (dir / "x.png").string();
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --frobnicate"), dir); }), 2,
      "frobnicate");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --spp 0"), dir); }), 2,
                        "--spp");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --spp -3"), dir); }), 2,
                        "--spp");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --width 2000000"), dir); }), 2,
      "--width");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --height 0"), dir); }),
                        2, "--height");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + kSpheres + out + " --spp many"), dir); }),
                        2, "--spp");
  expect_one_line_error(subject([&] { return run_command(stage1(out), dir); }), 2, "--scene");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + kSpheres + " --out " + (dir / "x.jpg").string()), dir); }),
      2, "unknown image format '.jpg'");
  EXPECT_FALSE(subject([&] { return std::filesystem::exists(dir / "x.png"); }));
}

TEST(Stage1Cli, BadInputExitsWithOneAndWritesNothing) {
  ScratchDir dir;
  const std::string out = " --out " + (dir / "x.png").string();
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + (dir / "missing.json").string() + out), dir); }), 1,
      "missing.json: cannot open scene file");
  testing::write_text(dir / "broken.json", "{ \"camera\": [1, 2");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + (dir / "broken.json").string() + out), dir); }), 1,
      "broken.json: malformed JSON");
  // The Cornell box is made of quads, which stage 1 does not render.
  expect_one_line_error(subject([&] {
                          return run_command(
                              stage1("--scene " + source_path("assets/scenes/cornell-box.json").string() + out), dir);
                        }),
                        1, "cornell-box.json: /shapes/0: stage 1 renders spheres, planes and tori only");
  // Mirrors and glass are stage 2's.
  testing::write_text(dir / "mirror.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40},
    "materials": {"silver": {"type": "mirror"}}, "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "silver"}]})");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + (dir / "mirror.json").string() + out), dir); }), 1,
      "mirror.json: /materials/silver: stage 1 shades diffuse materials only");
  EXPECT_FALSE(subject([&] { return std::filesystem::exists(dir / "x.png"); }));
}

// --filter, the lens keys, the display flags and EXR output, as a user meets them.
TEST(Stage1Cli, FiltersLensesDisplayFlagsAndExr) {
  ScratchDir dir;
  const std::string dof = source_path("assets/scenes/depth-of-field.json").string();
  const std::string small = " --width 32 --height 18 --spp 2 --threads 2";
  const auto exr = subject([&] {
    return run_command(stage1("--scene " + dof + small + " --filter mitchell --out " + (dir / "a.exr").string()), dir);
  });
  ASSERT_EQ(exr.exit_code, 0) << exr.err;
  EXPECT_EQ(subject([&] { return decode_exr(testing::read_text(dir / "a.exr"), "a.exr").width(); }), 32);
  const auto png = subject([&] {
    return run_command(
        stage1("--scene " + dof + small + " --exposure -1.5 --tone aces --gamma 2.2 --out " + (dir / "a.png").string()),
        dir);
  });
  EXPECT_EQ(png.exit_code, 0) << png.err;
  const std::string out = " --out " + (dir / "x.png").string();
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + dof + out + " --filter sinc"), dir); }), 2,
                        "--filter");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + dof + out + " --tone filmic"), dir); }), 2,
                        "--tone");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + dof + out + " --exposure nan"), dir); }),
                        2, "--exposure");
  expect_one_line_error(subject([&] { return run_command(stage1("--scene " + dof + out + " --gamma 0"), dir); }), 2,
                        "--gamma");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + dof + " --out " + (dir / "x.tiff").string()), dir); }), 2,
      ".exr");
  testing::write_text(dir / "lens.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40,
    "aperture_radius": -0.1}, "materials": {"m": {}}, "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + (dir / "lens.json").string() + out), dir); }), 1,
      "lens.json: /camera/aperture_radius: aperture radius must be in [0");
  testing::write_text(dir / "filter.json", R"({"render": {"filter": "lanczos"}, "camera": {"position": [0,0,-5],
    "look_at": [0,0,0], "vfov": 40}, "materials": {"m": {}}, "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + (dir / "filter.json").string() + out), dir); }), 1,
      "filter.json: /render/filter: unknown filter");
  EXPECT_FALSE(subject([&] { return std::filesystem::exists(dir / "x.png"); }));
}

TEST(Stage1Cli, UnwritableOutputFailsBeforeRendering) {
  ScratchDir dir;
  expect_one_line_error(subject([&] {
                          return run_command(
                              stage1("--scene " + kSpheres + " --out " + (dir / "no" / "dir.png").string()), dir);
                        }),
                        1, "does not exist");
  std::filesystem::create_directory(dir / "a.png");
  expect_one_line_error(
      subject([&] { return run_command(stage1("--scene " + kSpheres + " --out " + (dir / "a.png").string()), dir); }),
      1, "is a directory");
}

TEST(Stage1Cli, SameSeedSameImageWhateverTheThreads) {
  ScratchDir dir;
  const std::string base = stage1("--scene " + kSpheres + " --width 64 --height 40 --spp 3 --seed 5 ");
  ASSERT_EQ(
      subject([&] { return run_command(base + "--threads 1 --out " + (dir / "one.pfm").string(), dir); }).exit_code, 0);
  ASSERT_EQ(
      subject([&] { return run_command(base + "--threads 2 --out " + (dir / "two.pfm").string(), dir); }).exit_code, 0);
  EXPECT_EQ(subject([&] { return testing::read_text(dir / "one.pfm"); }),
            subject([&] { return testing::read_text(dir / "two.pfm"); }));
}

}  // namespace
}  // namespace rt
