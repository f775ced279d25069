// The stage-3 program: every accelerator renders the same picture, and reports its figures.
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

std::string stage3(const std::string& arguments) { return "'" + std::string(STAGE3_EXE) + "' " + arguments; }

TEST(Stage3Cli, EveryAcceleratorRendersTheSamePicture) {
  ScratchDir dir;
  const std::string scene = source_path("assets/scenes/whitted.json").string();
  std::vector<Image> images;
  for (const char* accel : {"naive", "median", "middle", "sah", "sah --wide", "sah --wide --compact"}) {
    const auto out = dir / (std::to_string(images.size()) + ".pfm");
    const auto r = subject([&] { return run_command(stage3("--scene " + scene + " --width 64 --height 40 --spp 1 --accel " + accel +
                                      " --out " + out.string()), dir); });
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("rays/s"), std::string::npos) << r.out;
    images.push_back(subject([&] { return read_pfm(out); }));
  }
  for (size_t i = 1; i < images.size(); ++i) {
    // The same primitive answers everywhere, except where a ray meets two triangles at exactly the
    // same t (a shared edge) and either may shade the pixel.
    int differing = 0;
    for (size_t p = 0; p < images[0].pixels().size(); ++p) differing += images[0].pixels()[p] != images[i].pixels()[p] ? 1 : 0;
    EXPECT_LE(differing, 3) << "accelerator " << i;
  }
}

TEST(Stage3Cli, SameImageForAnyThreadCount) {
  ScratchDir dir;
  const std::string base = "--scene " + source_path("assets/scenes/bunny.json").string() + " --width 32 --height 24 --spp 2";
  ASSERT_EQ(subject([&] { return run_command(stage3(base + " --threads 1 --out " + (dir / "one.pfm").string()), dir); }).exit_code, 0);
  ASSERT_EQ(subject([&] { return run_command(stage3(base + " --threads 2 --out " + (dir / "two.pfm").string()), dir); }).exit_code, 0);
  EXPECT_TRUE(subject([&] { return read_pfm(dir / "one.pfm") == read_pfm(dir / "two.pfm"); }));
}

TEST(Stage3Cli, ReportsTheTree) {
  ScratchDir dir;
  const auto r = subject([&] { return run_command(stage3("--scene " + source_path("assets/scenes/bunny.json").string() +
                                    " --width 32 --height 24 --spp 1 --accel median --leaf-size 8 --out " +
                                    (dir / "b.png").string()), dir); });
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* figure : {"69451 triangles", "leaf size 8", "nodes", "depth", "bytes per triangle", "rays/s"})
    EXPECT_NE(r.out.find(figure), std::string::npos) << figure << " in:\n" << r.out;
  const auto wide = subject([&] { return run_command(stage3("--scene " + source_path("assets/scenes/bunny.json").string() +
                                       " --width 32 --height 24 --spp 1 --wide --out " + (dir / "w.png").string()), dir); });
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.out.find("4-wide nodes"), std::string::npos) << wide.out;
}

TEST(Stage3Cli, RendersAMillionTriangles) {
  // Sixteen placed copies of the bunny: 1,111,216 triangles in one tree.
  ScratchDir dir;
  const auto r = subject([&] { return run_command(stage3("--scene " + source_path("assets/scenes/bunnies.json").string() +
                                    " --width 12 --height 8 --spp 1 --accel middle --out " + (dir / "b.png").string()), dir); });
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1111216 triangles"), std::string::npos) << r.out;
  EXPECT_TRUE(subject([&] { return std::filesystem::exists(dir / "b.png"); }));
}

TEST(Stage3Cli, BadFlagsAreUsageErrors) {
  ScratchDir dir;
  const std::string base = "--scene " + source_path("assets/scenes/whitted.json").string() + " --out " + (dir / "x.png").string();
  EXPECT_EQ(subject([&] { return run_command(stage3(base + " --accel kdtree"), dir); }).exit_code, 2);
  EXPECT_EQ(subject([&] { return run_command(stage3(base + " --leaf-size 0"), dir); }).exit_code, 2);
  EXPECT_EQ(subject([&] { return run_command(stage3(base + " --compact"), dir); }).exit_code, 2);  // a layout of the 4-wide tree's leaves
  EXPECT_EQ(subject([&] { return run_command(stage3(base + " --leaf-size 256"), dir); }).exit_code, 2);
  expect_one_line_error(subject([&] { return run_command(stage3("--scene " + (dir / "none.json").string() + " --out " + (dir / "x.png").string()), dir); }),
                        1, "none.json: cannot open scene file");
}

}  // namespace
}  // namespace rt
