// The stage-2 program as a user meets it: its flags, its scenes, and its errors.
#include "common/image_io.h"

#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

namespace rt {
namespace {

using testing::ScratchDir;
using testing::expect_one_line_error;
using testing::run_command;
using testing::source_path;
using testing::subject;
using testing::write_text;

std::string stage2(const std::string& arguments) { return "'" + std::string(STAGE2_EXE) + "' " + arguments; }
const std::string kWhitted = source_path("assets/scenes/whitted.json").string();

TEST(Stage2Cli, HelpListsTheStageFlags) {
  ScratchDir dir;
  const auto r = subject([&] { return run_command(stage2("--help"), dir); });
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--scene", "--spp", "--out", "--threads", "--seed", "--max-depth", "--fresnel",
                           "--offset", "--epsilon", "--triangle", "--debug"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST(Stage2Cli, DepthZeroTurnsMirrorsAndGlassBlack) {
  ScratchDir dir;
  const std::string size = " --width 48 --height 30 --spp 1 --threads 2";
  // The program's stderr goes into the failure message: it names the tasks still missing.
  const auto full_run = subject([&] { return run_command(stage2("--scene " + kWhitted + size + " --out " + (dir / "full.pfm").string()), dir); });
  ASSERT_EQ(full_run.exit_code, 0) << full_run.err;
  ASSERT_EQ(subject([&] { return run_command(stage2("--scene " + kWhitted + size + " --max-depth 0 --out " + (dir / "flat.pfm").string()), dir); }).exit_code, 0);
  const Image full = subject([&] { return read_pfm(dir / "full.pfm"); });
  const Image flat = subject([&] { return read_pfm(dir / "flat.pfm"); });
  int black_only_when_flat = 0;
  for (size_t i = 0; i < full.pixels().size(); ++i)
    if (flat.pixels()[i] == Color(0.0f) && full.pixels()[i] != Color(0.0f)) ++black_only_when_flat;
  EXPECT_GT(black_only_when_flat, 48 * 30 / 20) << "the mirror and glass balls cover part of the picture\n" << full_run.err;
}

TEST(Stage2Cli, EveryMethodFlagRenders) {
  ScratchDir dir;
  for (const std::string flags : {"--fresnel schlick", "--offset integer-ulp", "--offset fixed --epsilon 1e-3",
                                  "--triangle moller-trumbore", "--debug normal", "--debug depth", "--debug albedo"}) {
    const auto r = subject([&] { return run_command(stage2("--scene " + kWhitted + " --width 24 --height 16 --spp 1 " + flags +
                                      " --out " + (dir / "x.png").string()), dir); });
    EXPECT_EQ(r.exit_code, 0) << flags << ": " << r.err;
  }
}

TEST(Stage2Cli, BadInputIsOneLineNamingTheFile) {
  ScratchDir dir;
  write_text(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  write_text(dir / "scene.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40},
    "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "bad.obj", "material": "m"}]})");
  const auto bad_mesh = subject([&] { return run_command(stage2("--scene " + (dir / "scene.json").string() + " --out " + (dir / "o.png").string()), dir); });
  expect_one_line_error(bad_mesh, 1, (dir / "bad.obj").string() + ":3: vertex needs three finite coordinates, got 'nan'");
  EXPECT_FALSE(subject([&] { return std::filesystem::exists(dir / "o.png"); }));

  const auto torus = subject([&] { return run_command(stage2("--scene " + source_path("assets/scenes/spheres.json").string() + " --out " +
                                        (dir / "o.png").string()), dir); });
  expect_one_line_error(torus, 1, "/shapes/4: stage 2 renders spheres, planes, triangles, quads and meshes");

  write_text(dir / "glossy.json", R"({"camera": {"position": [0,0,-5], "look_at": [0,0,0], "vfov": 40},
    "materials": {"plastic": {"type": "phong"}}, "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "plastic"}]})");
  const auto glossy = subject([&] { return run_command(stage2("--scene " + (dir / "glossy.json").string() + " --out " + (dir / "o.png").string()), dir); });
  expect_one_line_error(glossy, 1, "glossy.json: /materials/plastic: stage 2 renders diffuse, mirror and dielectric materials");

  const auto usage = subject([&] { return run_command(stage2("--scene " + kWhitted + " --offset sometimes --out " + (dir / "o.png").string()), dir); });
  EXPECT_EQ(usage.exit_code, 2) << usage.err;
  const auto depth = subject([&] { return run_command(stage2("--scene " + kWhitted + " --max-depth -1 --out " + (dir / "o.png").string()), dir); });
  EXPECT_EQ(depth.exit_code, 2) << depth.err;
}

}  // namespace
}  // namespace rt
